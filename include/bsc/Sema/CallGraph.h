//===- CallGraph.h - the static call graph as Graphviz DOT -----*- C++ -*-===//
//
// `bsc --emit=graph` prints which func or task calls which, so that a
// behavior's hierarchy of tasks can be seen at a glance (`dot -Tsvg`). The
// graph is Sema's (Behavior::Calls): the writer only formats it, and a REPL
// can draw the same graph with the tasks of its last cycle highlighted.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_SEMA_CALLGRAPH_H
#define BSC_SEMA_CALLGRAPH_H

#include "bsc/Sema/Sema.h"
#include "llvm/ADT/DenseSet.h"

namespace llvm {
class SourceMgr;
class raw_ostream;
} // namespace llvm

namespace bsc {

/// Writes the call graph of a checked behavior as a Graphviz digraph: a
/// cluster per module; a node per func and task (nested funcs included),
/// in module and source order, named by its qualified name
/// (`Module::task`, `Module::task.nested`), tasks as boxes and funcs as
/// ellipses; an edge per caller and callee, in the order of their first
/// call, labelled with the lines of every call (`label="12, 17"`), which
/// `SM` decodes. The callables in `Active` (if given) are drawn filled.
void writeCallGraphDOT(
    const Behavior &B, const llvm::SourceMgr &SM, llvm::raw_ostream &OS,
    const llvm::DenseSet<const CallableDecl *> *Active = nullptr);

} // namespace bsc

#endif
