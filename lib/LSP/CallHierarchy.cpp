//===- CallHierarchy.cpp - who calls a task, and whom it calls -------------===//
//
// The hierarchy is what a behavior is: tasks calling tasks. Its edges are
// Sema's call sites (Behavior::Calls: the caller, the callee and the
// callee's name in the call), read from every analysis the server hands
// over, so that callers in modules the callee's module does not require
// are found too. The client hands an item back for its calls: its
// selection range names the task or func, whose definitionKey the call
// sites are matched by.
//
//===----------------------------------------------------------------------===//
#include "Describe.h"
#include "Features.h"
#include <map>
#include <set>

using namespace bsc;
using namespace bsc::lsp;

/// LSP's SymbolKind of a callable: as the outline shows them.
static int kindOf(const CallableDecl &C) {
  return llvm::isa<TaskDecl>(C) ? 24 /*Event*/ : 12 /*Function*/;
}

static std::string keyOf(const Analysis &A, const CallableDecl &C) {
  return definitionKey(A, Symbol{Symbol::Decl, &C, 0});
}

/// The item of a task or func, in the analysis that holds it.
static llvm::json::Object itemOf(const Analysis &A, const CallableDecl &C) {
  unsigned ID = A.C->SM.FindBufferContainingLoc(C.getName().getRange().Start);
  return llvm::json::Object{
      {"name", C.getName().Name.str()},
      {"detail", headerOf(A.C->SM, C)},
      {"kind", kindOf(C)},
      {"uri", pathToURI(A.getPath(ID))},
      {"range", A.getRange(C.getRange())},
      {"selectionRange", A.getRange(C.getName().getRange())}};
}

/// A call's name as written, from `Loc` (where Sema records it: the start
/// of `Moves::step`) to the end of the callee's own name.
static llvm::SMRange callRange(const Analysis &A, unsigned ID, llvm::SMLoc Loc,
                               const CallableDecl &Callee) {
  const char *End = A.C->SM.getMemoryBuffer(ID)->getBufferEnd();
  llvm::StringRef Rest(Loc.getPointer(),
                       std::min<size_t>(End - Loc.getPointer(), 256));
  llvm::StringRef Name = Callee.getName().Name;
  size_t At = Rest.find(Name);
  size_t Length = At == llvm::StringRef::npos ? Name.size() : At + Name.size();
  return {Loc, llvm::SMLoc::getFromPointer(Loc.getPointer() + Length)};
}

/// The task or func named at `Loc`, if one is.
static const CallableDecl *callableAt(const Analysis &A, llvm::SMLoc Loc) {
  const Occurrence *O = A.Idx.findAt(Loc);
  if (!O || O->Sym.K != Symbol::Decl)
    return nullptr;
  return llvm::dyn_cast<CallableDecl>(static_cast<const Decl *>(O->Sym.Ptr));
}

llvm::json::Value lsp::prepareCallHierarchy(const Analysis &A,
                                            llvm::SMLoc Loc) {
  const CallableDecl *C = callableAt(A, Loc);
  if (!C)
    return nullptr;
  return llvm::json::Array{itemOf(A, *C)};
}

llvm::json::Value lsp::hierarchyCalls(llvm::ArrayRef<const Analysis *> All,
                                      const Analysis &A, llvm::SMLoc Loc,
                                      bool Incoming) {
  const CallableDecl *Item = callableAt(A, Loc);
  std::string Key = Item ? keyOf(A, *Item) : "";
  if (Key.empty())
    return llvm::json::Array();
  // Per caller (incoming) or callee (outgoing), by key: its item and the
  // places of the calls, each once though several analyses see it.
  struct Calls {
    llvm::json::Object Item;
    llvm::json::Array Ranges;
    std::set<std::string> Seen;
  };
  std::map<std::string, Calls> ByOther;
  std::vector<std::string> Order;
  for (const Analysis *A : All)
    for (const CallSite &Site : A->C->Checked.Calls) {
      const CallableDecl &Self = Incoming ? *Site.Callee : *Site.Caller;
      const CallableDecl &Other = Incoming ? *Site.Caller : *Site.Callee;
      if (keyOf(*A, Self) != Key)
        continue;
      std::string OtherKey = keyOf(*A, Other);
      if (OtherKey.empty())
        continue;
      auto [It, New] = ByOther.try_emplace(OtherKey);
      if (New) {
        It->second.Item = itemOf(*A, Other);
        Order.push_back(OtherKey);
      }
      unsigned ID = A->C->SM.FindBufferContainingLoc(Site.Loc);
      std::string Place =
          A->getPath(ID) + ":" +
          std::to_string(Site.Loc.getPointer() -
                         A->C->SM.getMemoryBuffer(ID)->getBufferStart());
      if (It->second.Seen.insert(Place).second)
        It->second.Ranges.push_back(
            A->getRange(callRange(*A, ID, Site.Loc, *Site.Callee)));
    }
  llvm::json::Array Result;
  for (const std::string &K : Order) {
    Calls &C = ByOther[K];
    Result.push_back(llvm::json::Object{
        {Incoming ? "from" : "to", std::move(C.Item)},
        {"fromRanges", std::move(C.Ranges)}});
  }
  return Result;
}
