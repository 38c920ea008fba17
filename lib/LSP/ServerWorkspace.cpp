//===- ServerWorkspace.cpp - requests about the whole workspace ------------===//
//
// What looks beyond one document's place: workspace symbols, the edits
// that follow a module file's rename, the calls of the call hierarchy, and
// the check of a rename, which analyses the behavior again with the
// renamed texts standing in for the documents.
//
//===----------------------------------------------------------------------===//
#include "ServerImpl.h"
#include "llvm/Support/MemoryBuffer.h"

using namespace bsc;
using namespace bsc::lsp;

/// The analyses of every open document and the behaviors around them.
static std::vector<const Analysis *>
pointers(const std::vector<std::unique_ptr<Analysis>> &Own) {
  std::vector<const Analysis *> All;
  for (const auto &A : Own)
    All.push_back(A.get());
  return All;
}

bool Server::workspaceRequest(const llvm::json::Value &Id,
                              llvm::StringRef Method,
                              const llvm::json::Object *Params) {
  if (Method == "workspace/symbol") {
    std::vector<std::unique_ptr<Analysis>> Own;
    for (const auto &[Path, Text] : W.getOpen()) {
      std::unique_ptr<Analysis> A = W.analyze(Path);
      for (auto &B : relatedAnalyses(*A))
        Own.push_back(std::move(B));
      Own.push_back(std::move(A));
    }
    std::optional<llvm::StringRef> Query =
        Params ? Params->getString("query") : std::nullopt;
    reply(Id, workspaceSymbols(pointers(Own), Query.value_or("")));
    return true;
  }
  if (Method == "workspace/willRenameFiles") {
    reply(Id, willRenameFiles(Params));
    return true;
  }
  if (Method == "callHierarchy/incomingCalls" ||
      Method == "callHierarchy/outgoingCalls") {
    const llvm::json::Object *Item =
        Params ? Params->getObject("item") : nullptr;
    std::optional<llvm::StringRef> URI =
        Item ? Item->getString("uri") : std::nullopt;
    std::string Path = URI ? uriToPath(*URI) : "";
    const Analysis *A = Path.empty() ? nullptr : analysisOf(Path);
    unsigned Buffer = A ? A->getBuffer(Path) : 0;
    const llvm::json::Object *Range =
        Buffer ? Item->getObject("selectionRange") : nullptr;
    if (!Range) {
      replyError(Id, InvalidParams,
                 "the request needs an item prepareCallHierarchy gave: a "
                 "task or func of a b-script file");
      return true;
    }
    std::vector<std::unique_ptr<Analysis>> Others = relatedAnalyses(*A);
    std::vector<const Analysis *> All{A};
    for (const Analysis *O : pointers(Others))
      All.push_back(O);
    reply(Id, hierarchyCalls(All, *A, A->getLoc(Buffer, Range->get("start")),
                             Method == "callHierarchy/incomingCalls"));
    return true;
  }
  return false;
}

llvm::json::Value Server::willRenameFiles(const llvm::json::Object *Params) {
  // Each renamed module's `requires` and qualifiers, in every module of the
  // folders around it; the edits of several files merged.
  llvm::json::Object Changes;
  const llvm::json::Array *Files = Params ? Params->getArray("files") : nullptr;
  for (const llvm::json::Value &F : Files ? *Files : llvm::json::Array()) {
    const llvm::json::Object *File = F.getAsObject();
    std::optional<llvm::StringRef> Old =
        File ? File->getString("oldUri") : std::nullopt;
    std::optional<llvm::StringRef> New =
        File ? File->getString("newUri") : std::nullopt;
    std::string OldPath = Old ? uriToPath(*Old) : "";
    if (OldPath.empty() || !New)
      continue;
    std::unique_ptr<Analysis> A = W.analyze(OldPath);
    std::vector<std::unique_ptr<Analysis>> Others = relatedAnalyses(*A);
    std::vector<const Analysis *> All{A.get()};
    for (const Analysis *O : pointers(Others))
      All.push_back(O);
    llvm::json::Value Edit = renameModuleFile(All, OldPath, uriToPath(*New));
    if (const llvm::json::Object *E = Edit.getAsObject())
      for (const auto &[URI, List] : *E->getObject("changes"))
        for (const llvm::json::Value &Item : *List.getAsArray()) {
          if (!Changes.get(URI))
            Changes[URI] = llvm::json::Array();
          Changes.getArray(URI)->push_back(Item);
        }
  }
  if (Changes.empty())
    return nullptr;
  return llvm::json::Object{{"changes", std::move(Changes)}};
}

std::string Server::checkRename(llvm::ArrayRef<const Analysis *> All,
                                const Analysis &A, llvm::SMLoc Loc,
                                llvm::ArrayRef<Location> Occurrences,
                                llvm::StringRef NewName) {
  // The renamed texts stand in for the documents while the behavior is
  // checked again, then the documents are as they were.
  std::map<std::string, std::vector<const Location *>> ByPath;
  for (const Location &L : Occurrences)
    ByPath[L.Path].push_back(&L);
  struct Saved {
    std::string Path;
    std::optional<std::string> Text;
    int64_t Version;
  };
  std::vector<Saved> Restore;
  for (auto &[Path, Places] : ByPath) {
    std::string Text;
    std::string *Open = W.getText(Path);
    if (Open)
      Text = *Open;
    else if (auto Buf = llvm::MemoryBuffer::getFile(Path))
      Text = (*Buf)->getBuffer().str();
    else
      continue;
    Restore.push_back({Path, Open ? std::optional(*Open) : std::nullopt,
                       W.getVersion(Path).value_or(0)});
    // From the end, so that the offsets before stay true.
    llvm::sort(Places, [](const Location *X, const Location *Y) {
      return X->Begin > Y->Begin;
    });
    for (const Location *L : Places)
      if (L->End <= Text.size() && L->Begin <= L->End)
        Text.replace(L->Begin, L->End - L->Begin, NewName.str());
    W.open(Path, std::move(Text), 0);
  }
  // Each edited file checked as its behavior, before (All) and after.
  std::unique_ptr<Analysis> After = W.analyze(A.Path);
  std::vector<std::pair<const Analysis *, std::unique_ptr<Analysis>>> Checked;
  for (const auto &[Path, Places] : ByPath)
    if (Path != A.Path)
      for (const Analysis *Old : All)
        if (Old->Path == Path)
          Checked.push_back({Old, W.analyze(Path)});
  for (Saved &S : Restore) {
    if (S.Text)
      W.open(S.Path, std::move(*S.Text), S.Version);
    else
      W.close(S.Path);
  }

  auto NewError = [](const Analysis &Old, const Analysis &New) {
    std::set<std::string> Before;
    for (const Diagnostic &D : Old.C->Diags.getDiagnostics())
      if (D.Sev == Severity::Error)
        Before.insert(D.Message);
    for (const Diagnostic &D : New.C->Diags.getDiagnostics())
      if (D.Sev == Severity::Error && !Before.count(D.Message))
        return D.Message;
    return std::string();
  };
  std::string Error = NewError(A, *After);
  for (const auto &[Old, New] : Checked)
    if (Error.empty())
      Error = NewError(*Old, *New);
  if (!Error.empty())
    return "renaming to '" + NewName.str() +
           "' would make the behavior wrong: " + Error;

  // The cursor's place in the renamed text: moved by the renamed places
  // before it in its file.
  unsigned Buffer = A.C->SM.FindBufferContainingLoc(Loc);
  if (!Buffer)
    return "";
  std::string CursorPath = A.getPath(Buffer);
  int64_t Offset =
      Loc.getPointer() - A.C->SM.getMemoryBuffer(Buffer)->getBufferStart();
  const Location *Cursor = nullptr;
  for (const Location &L : Occurrences)
    if (L.Path == CursorPath && L.Begin <= Offset && Offset <= L.End)
      Cursor = &L;
  if (!Cursor)
    return "";
  int64_t NewOffset = Cursor->Begin;
  for (const Location &L : Occurrences)
    if (L.Path == CursorPath && L.End <= Cursor->Begin)
      NewOffset += int64_t(NewName.size()) - int64_t(L.End - L.Begin);
  unsigned NewBuffer = After->getBuffer(CursorPath);
  if (!NewBuffer ||
      size_t(NewOffset) > After->C->SM.getMemoryBuffer(NewBuffer)->getBufferSize())
    return "";
  llvm::SMLoc NewLoc = llvm::SMLoc::getFromPointer(
      After->C->SM.getMemoryBuffer(NewBuffer)->getBufferStart() + NewOffset);
  size_t Was = findOccurrences({&A}, A, Loc, true).size();
  size_t Is = findOccurrences({After.get()}, *After, NewLoc, true).size();
  if (Was != Is)
    return "renaming to '" + NewName.str() + "' would change what names " +
           "refer to: the name would be written in " + std::to_string(Is) +
           (Is == 1 ? " place" : " places") + " of this behavior instead of " +
           std::to_string(Was) +
           " (it would shadow, or be shadowed by, another declaration)";
  return "";
}
