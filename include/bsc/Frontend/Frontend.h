//===- Frontend.h - from source files to a checked behavior ----*- C++ -*-===//
//
// The front end of one compilation: read the files named on the command
// line, read the standard modules (`io`, from the runtime archive) and the
// binding objects (--bind) into native modules, parse the
// files, follow their `requires` to sibling `.bs` files (or native
// modules), and check the whole behavior. The driver, the JIT runner
// and the REPL all start here. Nothing here prints; diagnostics collect in
// the Compilation's DiagnosticEngine.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_FRONTEND_FRONTEND_H
#define BSC_FRONTEND_FRONTEND_H

#include "bsc/AST/AST.h"
#include "bsc/Basic/Diagnostic.h"
#include "bsc/Bind/Bind.h"
#include "bsc/Sema/Sema.h"
#include "llvm/Support/SourceMgr.h"
#include "llvm/TargetParser/Triple.h"
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace bsc {

/// A source file larger than this is refused before it is read: a behavior
/// module is a few kilobytes, and the limit keeps garbage input bounded.
constexpr unsigned MaxSourceFileMiB = 64;
/// A recording read whole (`--replay`, `bsc timeline`): 100,000 cycles of a
/// behavior with its tasks are some 70 MiB.
constexpr unsigned MaxRecordingMiB = 1024;
/// The most robots `--robots` runs in one process, and a team's recording
/// or log names.
constexpr unsigned MaxRobots = 1000;

/// The modules every target with a runtime provides (FrontendOptions::
/// StandardModules); named for the message when a target has none.
inline constexpr const char *StandardModuleNames[] = {"io"};

struct FrontendOptions {
  std::vector<std::string> Inputs;      ///< The .bs files named by the user.
  /// `bsc verify --model`: modules whose funcs stand for registered C++
  /// (docs/verify.md), loaded after the inputs; not part of the behavior
  /// (its hash), which never calls them.
  std::vector<std::string> Models;
  std::vector<std::string> IncludeDirs; ///< -I: searched after the requiring file's folder.
  /// The standard modules (`io`): binding objects or archives read like
  /// BindObjects and before them, so a --bind module of the same name is
  /// "registered twice". The driver names the runtime archive of Target.
  std::vector<std::string> StandardModules;
  /// A target with a runtime whose archive the driver did not find: its
  /// name and the folders it looked in (err_runtime_missing when the
  /// standard modules are needed).
  struct Missing {
    std::string Archive, SearchedIn;
  };
  std::optional<Missing> MissingRuntime;
  /// --bind: binding objects or archives (bindings.md), read for Target.
  std::vector<std::string> BindObjects;
  /// The compilation's target: sizes, offsets and the descriptor's pointer
  /// size depend on it. An empty triple means the host.
  llvm::Triple Target;
  /// Texts to read instead of the files of these paths (absolute, without
  /// `.` or `..`): the editor's unsaved documents, for the language server.
  const std::map<std::string, std::string> *Unsaved = nullptr;
};

/// Everything one compilation owns, alive until code generation is done.
struct Compilation {
  llvm::SourceMgr SM;
  ASTContext Ctx;
  DiagnosticEngine Diags;
  /// The modules of the standard and the binding objects.
  NativeRegistry Natives;
  /// What the standard and binding objects register, as lib/Bind read it
  /// (the module hashes and files for the back end; Natives holds the
  /// converted form).
  bind::BindingModel Bindings;
  /// Every module, the inputs first, then required ones as found.
  std::vector<ModuleAST *> Modules;
  /// Without binding objects: the names only they could define, reported
  /// together by loadModules or runFrontend (err_needs_binding).
  std::vector<UnboundName> Unbound;
  Behavior Checked;
};

/// Reads one source file into the SourceMgr; reports a missing, unreadable,
/// oversized file or a directory and returns 0 (buffer IDs start at 1).
unsigned addSourceFile(Compilation &C, llvm::StringRef Path,
                       unsigned MaxMiB = MaxSourceFileMiB);

/// The module name of a file: its name without the `.bs` extension.
std::string moduleNameForPath(llvm::StringRef Path);

/// Reads Opts.StandardModules and Opts.BindObjects for Opts.Target into
/// C.Bindings and adds their modules to C.Natives. A missing standard module
/// file is err_runtime_missing; each reader error becomes one
/// `bsc: error: ...` diagnostic of its kind (err_bind_*). Returns false if there was
/// an error.
bool readBindingObjects(Compilation &C, const FrontendOptions &Opts);

/// Reads the binding objects (readBindingObjects), then parses the inputs
/// and, transitively, the modules they require. A script
/// module is looked up as `<Name>.bs` in the requiring file's folder, then
/// in each -I folder; failing that, a native module of that name is used.
/// Cyclic `requires` are allowed: a behavior is compiled as a whole.
/// Returns false if an error was reported.
bool loadModules(Compilation &C, const FrontendOptions &Opts);

/// The file of script module `Name` as `requires` in `From` finds it:
/// `<Name>.bs` in From's folder, then in the -I folders. Returns "" if there
/// is none; `Searched` lists the folders tried (`'a', 'b'`).
std::string findScriptModule(const ModuleAST &From, llvm::StringRef Name,
                             llvm::ArrayRef<std::string> IncludeDirs,
                             std::string &Searched);

/// loadModules, then checkBehavior. Returns false if an error was reported.
bool runFrontend(Compilation &C, const FrontendOptions &Opts);

/// The entry of a program, a JIT run or the REPL, named by `Spec`
/// (`Module::name`, or `name` in the first input's module): it must exist
/// and take no parameters, and the world's `input` and `output` must be
/// constructible without arguments. Reports and returns null otherwise.
const CallableDecl *findProgramEntry(Compilation &C, llvm::StringRef Spec);

/// The funcs and tasks `bsc --export` names (`Module::name`, or `name` in
/// the first input's module; a name given twice counts once): each must be
/// top-level and callable from C (isCallableFromC). Reports and returns
/// std::nullopt otherwise.
std::optional<std::vector<const CallableDecl *>>
findExports(Compilation &C, llvm::ArrayRef<std::string> Specs);

/// --verify: compares the reported diagnostics with the `# expected-error
/// {{text}}` (also -warning, -note; `@+N`/`@-N` for another line) comments of
/// the source buffers. Each diagnostic must match an expectation on its line
/// whose text is a substring of its message, and each expectation must be
/// used once. Prints the differences to OS in clang's -verify format and
/// returns true when there are none (the driver then exits 0, even if the
/// expected diagnostics include errors).
bool verifyDiagnostics(const llvm::SourceMgr &SM,
                       llvm::ArrayRef<Diagnostic> Diags,
                       llvm::raw_ostream &OS);

/// 16 hex digits that change with the behavior's sources, what its binding
/// modules register (the same on every target: a robot's log names the
/// workstation's build of its behavior) and its entry: a recording whose
/// hash is the loaded behavior's replays exactly (docs/repl.md
/// "Recordings").
std::string computeBehaviorHash(const Compilation &C,
                                const CallableDecl &Entry);

} // namespace bsc

#endif
