//===- Behavior.h - a checked behavior, as data -----------------*- C++ -*-===//
//
// What Sema (bsc/Sema/Sema.h) hands the later phases: the modules compiled
// together and what they need without walking the tree again. Data only,
// beside the AST it points into, so that lib/Debug reads it without
// linking Sema.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_AST_BEHAVIOR_H
#define BSC_AST_BEHAVIOR_H

#include "bsc/AST/AST.h"
#include "llvm/Support/SMLoc.h"
#include <vector>

namespace bsc {

/// One call of a func or task in the body of another func or task: an edge
/// of the static call graph (`bsc --emit=graph`, the cycle check). Calls of
/// registered C++ functions and methods are not call sites here.
struct CallSite {
  /// The func or task whose body holds the call (a nested func, not its
  /// task, for a call in a nested func's body).
  const CallableDecl *Caller;
  const CallableDecl *Callee;
  /// The callee's name in the call, in the caller's file.
  llvm::SMLoc Loc;
};

/// A checked behavior: every module compiled together (whole program) and
/// what later phases need without walking the tree again.
struct Behavior {
  std::vector<ModuleAST *> Modules;
  /// Every task of every module, in module then source order.
  std::vector<TaskDecl *> Tasks;
  /// Every func, nested ones included, in module then source order.
  std::vector<FuncDecl *> Funcs;
  /// Every call of a func or task, grouped by caller in module and source
  /// order (a task, then its nested funcs), each caller's calls in source
  /// order. A call whose callee did not resolve is left out.
  std::vector<CallSite> Calls;
  /// Every `assert`, with the func or task whose body holds it, in module
  /// and source order: assertion k's counter with --assertions=count.
  struct Assertion {
    const AssertStmt *S;
    const CallableDecl *Owner;
  };
  std::vector<Assertion> Assertions;
  /// The native modules some module requires.
  std::vector<const NativeModule *> NativeModules;
  /// The module declaring `input`/`output`, if the registry has one.
  const NativeModule *World = nullptr;
  /// Every module read from a binding object (NativeModule::File is set)
  /// that the behavior was checked against, required or not: the object
  /// records their descriptor hashes for the load-time staleness check.
  std::vector<const NativeModule *> BindingModules;
  /// Whether some local, parameter, result or expression has a registered
  /// class type (`input` and `output` included): the back end must then
  /// lay out and call class values.
  bool UsesClasses = false;
};

} // namespace bsc

#endif
