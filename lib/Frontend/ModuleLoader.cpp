//===- ModuleLoader.cpp - reading files and resolving `requires` ----------===//
//
// A behavior is compiled as a whole, so the loader gathers every module
// reachable through `requires` before Sema runs. Modules are keyed by name:
// one name is one module in a behavior, whichever file asked for it.
//
//===----------------------------------------------------------------------===//
#include "bsc/Frontend/Frontend.h"
#include "bsc/Parse/Parser.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/ADT/StringSet.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/Path.h"
#include "llvm/TargetParser/Host.h"

using namespace bsc;

std::string bsc::moduleNameForPath(llvm::StringRef Path) {
  llvm::StringRef Name = llvm::sys::path::filename(Path);
  Name.consume_back(".bs");
  return Name.str();
}

static bool isIdentifier(llvm::StringRef S) {
  if (S.empty() || !(llvm::isAlpha(S[0]) || S[0] == '_'))
    return false;
  return llvm::all_of(S, [](char C) { return llvm::isAlnum(C) || C == '_'; });
}

unsigned bsc::addSourceFile(Compilation &C, llvm::StringRef Path,
                           unsigned MaxMiB) {
  if (llvm::sys::fs::is_directory(Path)) {
    C.Diags.report(llvm::SMLoc(), diag::err_file_is_directory) << Path;
    return 0;
  }
  uint64_t Size = 0;
  if (!llvm::sys::fs::file_size(Path, Size) &&
      Size > uint64_t(MaxMiB) * 1024 * 1024) {
    C.Diags.report(llvm::SMLoc(), diag::err_file_too_large) << Path << MaxMiB;
    return 0;
  }
  // Not a null-terminated view: the lexer works on the buffer's bounds, and
  // a NUL byte inside the file is just an invalid character.
  auto BufOrErr = llvm::MemoryBuffer::getFile(Path, /*IsText=*/false,
                                              /*RequiresNullTerminator=*/false);
  if (!BufOrErr) {
    C.Diags.report(llvm::SMLoc(), diag::err_cannot_open_file)
        << Path << BufOrErr.getError().message();
    return 0;
  }
  return C.SM.AddNewSourceBuffer(std::move(*BufOrErr), llvm::SMLoc());
}

std::string bsc::findScriptModule(const ModuleAST &From, llvm::StringRef Name,
                                  llvm::ArrayRef<std::string> IncludeDirs,
                                  std::string &Searched) {
  llvm::SmallVector<std::string, 4> Dirs;
  llvm::StringRef Parent = llvm::sys::path::parent_path(From.Path);
  Dirs.push_back(Parent.empty() ? "." : Parent.str());
  // A folder given twice (`-I` of the file's own) is tried and named once.
  for (const std::string &Dir : IncludeDirs)
    if (!llvm::is_contained(Dirs, Dir))
      Dirs.push_back(Dir);
  for (const std::string &Dir : Dirs) {
    llvm::SmallString<128> Candidate(Dir);
    llvm::sys::path::append(Candidate, Name + ".bs");
    if (llvm::sys::fs::is_regular_file(Candidate))
      return std::string(Candidate);
    if (!Searched.empty())
      Searched += ", ";
    Searched += "'" + Dir + "'";
  }
  return "";
}

namespace {
/// Loads modules by name, breadth first from the inputs.
class ModuleLoader {
public:
  ModuleLoader(Compilation &C, const FrontendOptions &Opts)
      : C(C), Opts(Opts) {}

  void loadInputs() {
    for (const std::string &Path : Opts.Inputs)
      loadFile(Path);
    // A model the behavior also requires (or named twice) stays what it
    // was first.
    for (const std::string &Path : Opts.Models) {
      size_t Before = C.Modules.size();
      if (ModuleAST *M = loadFile(Path); M && C.Modules.size() > Before)
        M->IsModel = true;
    }
    // Modules grows while requires are resolved; index, not iterate.
    for (size_t I = 0; I != C.Modules.size(); ++I)
      resolveRequires(*C.Modules[I]);
  }

private:
  ModuleAST *loadFile(llvm::StringRef Path) {
    std::string Name = moduleNameForPath(Path);
    if (!isIdentifier(Name)) {
      C.Diags.report(llvm::SMLoc(), diag::err_bad_module_file_name)
          << Name << Path;
      return nullptr;
    }
    auto It = ByName.find(Name);
    if (It != ByName.end()) {
      if (!llvm::sys::fs::equivalent(It->second->Path, Path)) {
        C.Diags.report(llvm::SMLoc(), diag::err_duplicate_module) << Name;
        C.Diags.report(llvm::SMLoc(), diag::note_other_module_file)
            << Name << It->second->Path;
      }
      return It->second;
    }
    unsigned BufferID = addUnsavedFile(Path);
    if (!BufferID)
      BufferID = addSourceFile(C, Path);
    if (!BufferID)
      return nullptr;
    ModuleAST *M = parseModule(C.SM, BufferID, Name, C.Ctx, C.Diags);
    M->Path = Path.str();
    ByName[Name] = M;
    C.Modules.push_back(M);
    return M;
  }

  /// The editor's text of `Path`, if it has one (FrontendOptions::Unsaved).
  unsigned addUnsavedFile(llvm::StringRef Path) {
    if (!Opts.Unsaved)
      return 0;
    llvm::SmallString<256> Abs(Path);
    llvm::sys::fs::make_absolute(Abs);
    llvm::sys::path::remove_dots(Abs, /*remove_dot_dot=*/true);
    auto It = Opts.Unsaved->find(std::string(Abs));
    if (It == Opts.Unsaved->end())
      return 0;
    return C.SM.AddNewSourceBuffer(
        llvm::MemoryBuffer::getMemBufferCopy(It->second, Path), llvm::SMLoc());
  }

  void resolveRequires(ModuleAST &M) {
    llvm::StringSet<> Seen;
    for (RequireDecl &R : M.Requires) {
      if (!Seen.insert(R.Name).second)
        C.Diags.report(R.Range.Start, diag::warn_duplicate_require)
            << R.Name << R.Range;
      if (R.Name == M.Name) {
        C.Diags.report(R.Range.Start, diag::err_require_self)
            << R.Name << R.Range;
        continue;
      }
      std::string Searched;
      if (std::string Path = findScriptModule(M, R.Name, Opts.IncludeDirs, Searched);
          !Path.empty()) {
        R.Script = loadFile(Path);
        continue;
      }
      if ((R.Native = C.Natives.find(R.Name)))
        continue;
      // Without --bind a module no file defines is likely a binding's.
      if (Opts.BindObjects.empty() &&
          !llvm::is_contained(StandardModuleNames, R.Name)) {
        C.Unbound.push_back({UnboundName::Module, R.Name, R.Range, Searched});
        continue;
      }
      C.Diags.report(R.Range.Start, diag::err_unknown_module)
          << R.Name << Searched << R.Range;
      if (Opts.StandardModules.empty() &&
          llvm::is_contained(StandardModuleNames, R.Name))
        C.Diags.report(R.Range.Start, diag::note_no_standard_module)
            << R.Name << Opts.Target.str();
    }
  }

  Compilation &C;
  const FrontendOptions &Opts;
  std::map<std::string, ModuleAST *> ByName;
};
} // namespace

/// Whether a module's File ("x.o" or "lib.a(x.o)") is one of the runtime
/// archives that hold the standard modules.
static bool isFromStandardModule(llvm::StringRef File,
                                 llvm::ArrayRef<std::string> Standard) {
  return llvm::any_of(Standard, [&](const std::string &Archive) {
    return File == Archive || File.starts_with(Archive + "(");
  });
}

bool bsc::readBindingObjects(Compilation &C, const FrontendOptions &Opts) {
  // The standard modules live in the runtime: a missing one is the
  // installation's problem, reported as linking reports it.
  if (Opts.MissingRuntime) {
    C.Diags.report(llvm::SMLoc(), diag::err_runtime_missing)
        << Opts.MissingRuntime->Archive << Opts.MissingRuntime->SearchedIn;
    return false;
  }
  // One reading of all objects: a --bind module named like a standard one
  // is then "registered twice", as between two --bind objects.
  std::vector<std::string> Paths = Opts.StandardModules;
  Paths.insert(Paths.end(), Opts.BindObjects.begin(), Opts.BindObjects.end());
  if (Paths.empty())
    return true;
  llvm::Triple Target = Opts.Target;
  if (Target.str().empty())
    Target = llvm::Triple(llvm::sys::getProcessTriple());
  llvm::Expected<bind::BindingModel> Model = bind::readBindings(Paths, Target);
  if (!Model) {
    llvm::handleAllErrors(Model.takeError(), [&](const bind::BindingError &E) {
      for (const bind::BindProblem &P : E.Problems) {
        DiagnosticBuilder D = C.Diags.report(llvm::SMLoc(), P.Kind);
        for (const std::string &Arg : P.Args)
          D << Arg;
      }
    });
    return false;
  }
  C.Bindings = std::move(*Model);
  // Members b-script cannot call (out parameters) are left out; naming one
  // is then an unknown member.
  bind::addToNativeRegistry(C.Bindings, C.Natives);
  for (auto &NM : C.Natives.Modules)
    NM->Standard = isFromStandardModule(NM->File, Opts.StandardModules);
  return true;
}

/// Reports the one name collected in C.Unbound with its own error.
static void reportUnboundName(Compilation &C, const UnboundName &N) {
  switch (N.K) {
  case UnboundName::Module:
    C.Diags.report(N.Range.Start, diag::err_unknown_module)
        << N.Name << N.SearchedIn << N.Range;
    break;
  case UnboundName::Input:
  case UnboundName::Output:
    C.Diags.report(N.Range.Start, N.K == UnboundName::Input
                                      ? diag::err_no_input_type
                                      : diag::err_no_output_type)
        << N.Range;
    break;
  case UnboundName::Qualifier:
    C.Diags.report(N.Range.Start, diag::err_unknown_qualifier)
        << N.Name << N.Range;
    C.Diags.report(N.Range.Start, diag::note_maybe_unbound) << N.Name;
    break;
  }
}

/// Reports the names collected in C.Unbound and clears them: one name with
/// its own error, several (one cause: no --bind) as one error at the first
/// with a note at each, in the reader's order (files as loaded, then
/// position). Returns false if there were any.
static bool reportUnbound(Compilation &C) {
  if (C.Unbound.empty())
    return true;
  if (C.Unbound.size() == 1) {
    reportUnboundName(C, C.Unbound.front());
    C.Unbound.clear();
    return false;
  }
  auto Place = [&](const UnboundName &N) {
    llvm::SMLoc L = N.Range.Start;
    return std::pair(C.SM.FindBufferContainingLoc(L), L.getPointer());
  };
  llvm::stable_sort(C.Unbound, [&](const UnboundName &A, const UnboundName &B) {
    return Place(A) < Place(B);
  });
  C.Diags.report(C.Unbound.front().Range.Start, diag::err_needs_binding)
      << C.Unbound.front().Range;
  for (const UnboundName &N : C.Unbound) {
    switch (N.K) {
    case UnboundName::Module:
      C.Diags.report(N.Range.Start, diag::note_unbound_module)
          << N.Name << N.SearchedIn << N.Range;
      break;
    case UnboundName::Input:
    case UnboundName::Output:
      C.Diags.report(N.Range.Start, diag::note_unbound_world)
          << N.Name
          << (N.K == UnboundName::Input ? "registerInput" : "registerOutput")
          << N.Range;
      break;
    case UnboundName::Qualifier:
      C.Diags.report(N.Range.Start, diag::note_unbound_qualifier)
          << N.Name << N.Range;
      break;
    }
  }
  C.Unbound.clear();
  return false;
}

/// loadModules without reporting C.Unbound, which runFrontend reports with
/// what checkBehavior adds.
static bool loadModulesCollecting(Compilation &C, const FrontendOptions &Opts) {
  unsigned ErrorsBefore = C.Diags.getNumErrors();
  if (Opts.Inputs.empty()) {
    C.Diags.report(llvm::SMLoc(), diag::err_no_input_files);
    return false;
  }
  if (!readBindingObjects(C, Opts))
    return false;
  ModuleLoader(C, Opts).loadInputs();
  return C.Diags.getNumErrors() == ErrorsBefore && C.Unbound.empty();
}

bool bsc::loadModules(Compilation &C, const FrontendOptions &Opts) {
  bool Loaded = loadModulesCollecting(C, Opts);
  return reportUnbound(C) && Loaded;
}

bool bsc::runFrontend(Compilation &C, const FrontendOptions &Opts) {
  bool Loaded = loadModulesCollecting(C, Opts);
  if (C.Modules.empty() || C.Diags.tooManyErrors()) {
    reportUnbound(C);
    return false;
  }
  // Sema runs even after parse errors (they left error nodes, which are
  // poison) so that one run reports as many independent mistakes as it can.
  auto FindModuleFile = [&](const ModuleAST &From, llvm::StringRef Name) {
    std::string Searched;
    return !findScriptModule(From, Name, Opts.IncludeDirs, Searched).empty();
  };
  bool Checked =
      checkBehavior(C.Modules, C.Ctx, C.Diags, C.Checked, &C.Natives,
                    FindModuleFile,
                    Opts.BindObjects.empty() ? &C.Unbound : nullptr);
  Checked &= reportUnbound(C);
  C.Diags.sortBySource(C.SM);
  return Loaded && Checked;
}

/// Finds `Module::name`, or `name` in the first input's module, among the
/// top-level funcs and tasks; null if there is none.
static const CallableDecl *findTopLevel(Compilation &C, llvm::StringRef Spec) {
  auto [ModName, Name] = Spec.rsplit("::");
  if (Name.empty() && !Spec.contains("::")) {
    Name = Spec;
    ModName = C.Modules.empty() ? "" : llvm::StringRef(C.Modules.front()->Name);
  }
  for (ModuleAST *M : C.Checked.Modules) {
    if (M->Name != ModName)
      continue;
    for (CallableDecl *D : M->Decls)
      if (D->getName().Name == Name)
        return D;
  }
  return nullptr;
}

/// Finds --entry.
static const CallableDecl *findEntry(Compilation &C, llvm::StringRef Spec) {
  const CallableDecl *D = findTopLevel(C, Spec);
  if (!D)
    C.Diags.report(llvm::SMLoc(), diag::err_no_entry) << Spec;
  return D;
}

std::optional<std::vector<const CallableDecl *>>
bsc::findExports(Compilation &C, llvm::ArrayRef<std::string> Specs) {
  std::vector<const CallableDecl *> Exports;
  bool OK = true;
  for (const std::string &Spec : Specs) {
    const CallableDecl *D = findTopLevel(C, Spec);
    if (!D) {
      C.Diags.report(llvm::SMLoc(), diag::err_no_export) << Spec;
      OK = false;
    } else if (!isCallableFromC(*D)) {
      C.Diags.report(D->getName().Loc, diag::err_export_not_callable_from_c)
          << D->getQualifiedName();
      OK = false;
    } else if (!llvm::is_contained(Exports, D)) {
      Exports.push_back(D);
    }
  }
  if (!OK)
    return std::nullopt;
  return Exports;
}

// A class without default constructor may only start as zero bytes if it
// copies as bytes and is trivially destructible, as Sema's
// checkDefaultConstructible says.
const CallableDecl *bsc::findProgramEntry(Compilation &C,
                                          llvm::StringRef Spec) {
  if (const NativeModule *World = C.Checked.World) {
    bool OK = true;
    for (auto [Name, Class] :
         {std::pair("input", World->Input), std::pair("output", World->Output)})
      if (Class && !Class->DefaultConstructible &&
          !(Class->CopiesAsBytes && Class->TriviallyDestructible)) {
        C.Diags.report(llvm::SMLoc(), diag::err_world_not_default_constructible)
            << Name << Class->QualifiedName;
        OK = false;
      }
    if (!OK)
      return nullptr;
  }
  const CallableDecl *Entry = findEntry(C, Spec);
  if (Entry && !Entry->Params.empty()) {
    C.Diags.report(Entry->getLoc(), diag::err_entry_has_params)
        << Entry->getQualifiedName();
    return nullptr;
  }
  return Entry;
}

