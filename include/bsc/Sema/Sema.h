//===- Sema.h - checking a behavior ----------------------------*- C++ -*-===//
#ifndef BSC_SEMA_SEMA_H
#define BSC_SEMA_SEMA_H

#include "bsc/AST/AST.h"
#include "bsc/Basic/Diagnostic.h"

namespace bsc {

/// A checked behavior: every module compiled together (whole program) and
/// what later phases need without walking the tree again.
struct Behavior {
  std::vector<ModuleAST *> Modules;
  /// Every task of every module, in module then source order.
  std::vector<TaskDecl *> Tasks;
  /// Every func, nested ones included, in module then source order.
  std::vector<FuncDecl *> Funcs;
  /// The native modules some module requires.
  std::vector<const NativeModule *> NativeModules;
};

/// Checks the modules (their `requires` already resolved by the module
/// loader): names, types, the task rules and the call graph. Fills in the
/// "Sema:" fields of the AST and `Out`. Returns false if it reported an
/// error to `Diags`.
bool checkBehavior(llvm::ArrayRef<ModuleAST *> Modules, ASTContext &Ctx,
                   DiagnosticEngine &Diags, Behavior &Out);

} // namespace bsc

#endif
