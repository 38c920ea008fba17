//===- Load.cpp - a behavior into the JIT, a session, a world ------------===//
//
// The same path serves `bsc run` and the REPL: generate the behavior for
// the host with probes (CodeGenOptions::Probes), link the standard modules
// and bindings as a program links them, start a session (Team.cpp starts
// a team of them and attaches a world library).
//
//===----------------------------------------------------------------------===//
#include "bsc/Run/Run.h"
#include "bsc/Bind/Bind.h"
#include "bsc/CodeGen/Target.h"
#include "llvm/ADT/StringSet.h"
#include "llvm/Demangle/Demangle.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/xxhash.h"

using namespace bsc;

/// Reports the link errors that are the user's to fix (a library the loader
/// refuses, a function no --bind file defines) and returns the rest.
static llvm::Error reportBindingLinkErrors(Compilation &C, llvm::Error E) {
  return llvm::handleErrors(
      std::move(E),
      [&](const BindingLoadError &BL) {
        C.Diags.report(llvm::SMLoc(), diag::err_bind_load)
            << BL.Path << BL.Message;
      },
      [&](const MissingSymbolsError &MS) {
        for (const std::string &S : MS.Symbols)
          C.Diags.report(llvm::SMLoc(), diag::err_jit_undefined_symbol)
              << llvm::demangle(S);
      });
}

llvm::Expected<std::unique_ptr<LoadedBehavior>>
bsc::loadBehavior(Compilation &C, const CallableDecl &Entry,
                  const LoadOptions &Opts) {
  auto L = std::make_unique<LoadedBehavior>();
  auto JITOrErr = BehaviorJIT::create(Opts.OptLevel, Opts.DebugInfo);
  if (!JITOrErr)
    return JITOrErr.takeError();
  L->JIT = std::move(*JITOrErr);
  BehaviorJIT &JIT = *L->JIT;

  CodeGenOptions CGOpts;
  CGOpts.BehaviorName = C.Modules.front()->Name;
  CGOpts.Probes = Opts.Probes;
  CGOpts.Boundary = true;
  CGOpts.ExternalFunctions = Opts.ExternalFunctions;
  CGOpts.DebugInfo = Opts.DebugInfo;
  CGOpts.Sources = &C.SM;
  CGOpts.OptLevel = Opts.OptLevel;
  CGOpts.CycleBudget = Opts.CycleBudget;
  CGOpts.Explain = Opts.Explain;
  CGOpts.Coverage = Opts.Coverage;
  CGOpts.Assertions = AssertionMode::Report;
  // The JIT calls the entry only.
  CGOpts.Exports.emplace();
  if (isCallableFromC(Entry))
    CGOpts.Exports->push_back(&Entry);
  auto Ctx = std::make_unique<llvm::LLVMContext>();
  std::unique_ptr<llvm::Module> M = emitLLVM(
      C.Checked, *Ctx, JIT.getTriple(), JIT.getDataLayout(), CGOpts, L->Layout);
  if (llvm::Error E = verifyGeneratedModule(*M))
    return E;
  L->Entry = &Entry;
  L->EntrySymbol = getEntrySymbol(CGOpts.BehaviorName, Entry);
  L->Tables = debug::buildDebugTables(C.Checked, L->Layout, C.SM);
  std::vector<std::string> Imports = bind::getBindingImports(
      C.Checked.BindingModules, getUndefinedSymbols(*M));
  if (!bind::checkBindingImports(C.Diags, Imports, Opts.BindObjects))
    return nullptr;
  // The standard modules' thunks from the host runtime archive, then the
  // --bind objects, as a program links them.
  for (const std::string &Path : Opts.StandardModules)
    if (llvm::Error E = JIT.addArchive(Path))
      return E;
  for (const std::string &Path : Opts.BindObjects)
    if (llvm::Error E = JIT.addObjectFile(Path)) {
      if (llvm::Error Internal = reportBindingLinkErrors(C, std::move(E)))
        return Internal;
      return nullptr;
    }
  // Link the bindings the behavior calls before its own code: a function
  // that a binding object calls and no --bind file defines (it is in
  // another object of the robot build) is the user's to fix, and the
  // behavior must never run with it unresolved.
  if (llvm::Error E = JIT.link(Imports)) {
    if (llvm::Error Internal = reportBindingLinkErrors(C, std::move(E)))
      return Internal;
    return nullptr;
  }
  if (llvm::Error E = JIT.addModule(std::move(M), std::move(Ctx), Opts.OptLevel))
    return E;
  L->Hash = computeBehaviorHash(C, Entry);
  if (Opts.Explain)
    L->ExplainLog =
        static_cast<ExplainLogHeader *>(JIT.lookup(ExplainLogSymbol));
  if (const NativeModule *World = C.Checked.World) {
    L->InputClass = World->Input;
    L->OutputClass = World->Output;
    for (auto [Class, Obj] : {std::pair(World->Input, &L->Input),
                              std::pair(World->Output, &L->Output)})
      if (Class)
        *Obj = {size_t(Class->Size), size_t(Class->Align), Class->Construct,
                Class->TriviallyDestructible ? "" : Class->Destroy};
  }
  return L;
}

llvm::Expected<std::unique_ptr<BehaviorSession>>
bsc::startSession(Compilation &C, LoadedBehavior &L) {
  auto S = BehaviorSession::start(*L.JIT, L.Layout.InfoSymbol, L.EntrySymbol,
                                  L.Input, L.Output);
  if (S)
    return S;
  // A stale binding module is the user's to fix, not an internal error.
  llvm::Error E = llvm::handleErrors(S.takeError(), [&](const StaleBindingError &SB) {
    C.Diags.report(llvm::SMLoc(), diag::err_stale_binding_module) << SB.Module;
  });
  if (E)
    return E;
  return nullptr;
}

int bsc::openWorldOutput(Compilation &C, llvm::StringRef Path) {
  int Fd;
  if (std::error_code EC = llvm::sys::fs::openFileForWrite(Path, Fd)) {
    C.Diags.report(llvm::SMLoc(), diag::err_cannot_write_output)
        << Path << EC.message();
    return -1;
  }
  return Fd;
}
