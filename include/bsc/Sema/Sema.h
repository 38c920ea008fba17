//===- Sema.h - checking a behavior ----------------------------*- C++ -*-===//
//
// The third phase: the parsed modules of a behavior, checked together
// (whole program). Sema resolves names across modules and the registered
// C++ (bsc/Bind), types every expression, enforces the task rules of
// docs/language.md (a task is called, not stored; its state is read with
// taskState; no recursion through tasks), folds constants, and records what
// later phases need in a Behavior: the tasks, the call graph, the entry.
// Errors go to the DiagnosticEngine; a behavior with errors is not handed
// to CodeGen. The REPL's lines are checked by the same code (SemaRepl.cpp)
// against the loaded behavior.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_SEMA_SEMA_H
#define BSC_SEMA_SEMA_H

#include "bsc/AST/AST.h"
#include "bsc/AST/Behavior.h"
#include "bsc/Basic/Diagnostic.h"
#include "llvm/ADT/DenseSet.h"
#include "llvm/ADT/STLFunctionalExtras.h"
#include <memory>
#include <optional>

namespace bsc {

/// A name that only a binding object can define (`input`, `output`, a
/// required module or a qualifier no script declares), used in a behavior
/// compiled without any: the front end collects them instead of reporting
/// each, and says once that binding objects are missing
/// (err_needs_binding), with a note at each.
struct UnboundName {
  enum Kind { Module, Input, Output, Qualifier } K;
  std::string Name;
  llvm::SMRange Range;
  std::string SearchedIn; ///< Module: the folders searched for its file.
};

/// Checks the modules (their `requires` already resolved by the module
/// loader): names, types, the task rules and the call graph. Fills in the
/// "Sema:" fields of the AST and `Out`. Returns false if it reported an
/// error to `Diags`.
///
/// `Natives` is every native module of the compilation (the standard `io`
/// and the --bind modules, see Native.h); null means none. It decides which module names are known and which module is the
/// world module (the one declaring `input`/`output`), whose classes and
/// enums are visible unqualified in every module and whose name works as a
/// qualifier without `requires`. Other native modules are reached through
/// the `requires` the loader resolved.
///
/// `FindModuleFile` tells whether `requires "Name"` in a module would find
/// a file (the module loader's search): a qualifier naming such a module
/// without the `requires` is then err_module_not_required.
///
/// `Unbound`, given when the compilation has no binding object, receives
/// the uses of `input`, `output` and (when no required module comes from
/// a file) unknown qualifiers, each name once, instead of their errors;
/// checkBehavior then returns false.
using ModuleFileFinder =
    llvm::function_ref<bool(const ModuleAST &From, llvm::StringRef Name)>;
bool checkBehavior(llvm::ArrayRef<ModuleAST *> Modules, ASTContext &Ctx,
                   DiagnosticEngine &Diags, Behavior &Out,
                   const NativeRegistry *Natives = nullptr,
                   ModuleFileFinder FindModuleFile = nullptr,
                   std::vector<UnboundName> *Unbound = nullptr);

/// Whether C can call a func or task as an entry of the compiled object:
/// every parameter is int, float or bool, and the result is not a class
/// value (include/bscript/bscript.h).
bool isCallableFromC(const CallableDecl &D);

/// The roots of the behavior: every top-level func and task callable from
/// C that no func or task of the behavior calls, in module and source
/// order. They are what an object exports unless told otherwise
/// (`bsc --export`): the rest is internal, so that the optimiser may inline
/// it into its callers.
std::vector<const CallableDecl *> findBehaviorRoots(const Behavior &B);

namespace sema {
class Sema;
} // namespace sema

/// Checks the lines typed at `bsc repl` against a behavior checkBehavior
/// accepted, as the body of a new func in the scope of one of its modules
/// (the entry's: its funcs, tasks and `requires` are visible; every other
/// loaded module is reachable qualified, `Math::between(...)`). What the
/// REPL allows beyond a func body: writing `input` and reading `output`
/// (between cycles the debugger plays the world), reading a task's kept
/// parameters and locals (`Striker.state`, `Striker::Striker.state`), an
/// expression of any type as a statement (its value is shown), and
/// variables that outlive the line (visible to every later line).
class ReplChecker {
public:
  ReplChecker(ASTContext &Ctx, DiagnosticEngine &Diags, const Behavior &B,
              const NativeRegistry *Natives, ModuleAST *Context);
  ~ReplChecker();

  /// The parameters and locals of tasks that lines may read (`Task.x`, and
  /// unqualified in the task's frame): the ones the state keeps
  /// (BehaviorLayout's frame fields; with the JIT's probes, all). Until
  /// set, none.
  void setFrameFields(llvm::DenseSet<const Decl *> Kept);
  /// `:frame T`: later lines are checked in T's module, with T's kept
  /// parameters and locals and its nested funcs visible unqualified; null
  /// returns to the context module.
  void setFrame(const TaskDecl *T);
  const TaskDecl *getFrame() const { return Frame; }

  /// A checked line: the func to generate and run once.
  struct Line {
    FuncDecl *Func = nullptr;
    /// The last statement was an expression with a value: this local of
    /// Func (not visible to later lines) holds it.
    VarDecl *Result = nullptr;
    /// Variables the line declares; they stay visible to later lines.
    std::vector<VarDecl *> NewVars;
  };
  /// Checks `Body` (from parseReplLine) as line number `Number`; std::nullopt
  /// after reporting an error. A line with an error declares nothing.
  std::optional<Line> check(BlockStmt *Body, unsigned Number);

  /// Every variable declared so far, oldest first.
  llvm::ArrayRef<VarDecl *> getVariables() const { return Vars; }

private:
  ASTContext &Ctx;
  ModuleAST *Context;
  const TaskDecl *Frame = nullptr;
  Behavior Scratch; ///< What the checker's Sema records; unused.
  std::unique_ptr<sema::Sema> S;
  std::vector<VarDecl *> Vars;
};

} // namespace bsc

#endif
