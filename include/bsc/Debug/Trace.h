//===- Trace.h - which tasks ran in a cycle, and where they stopped -*- C++ -*-===//
//
// A cycle's activation: the tasks called in it (frame.last_call holds the
// state's cycle, bit 31 aside), each with the state it left and the yield it is
// suspended at. The runtime takes it from a state with bs_trace_snapshot
// (bscript.h), on the robot as in the JIT, so the same records serve
// `bsc run --trace`, the REPL's `:tasks` and a robot log decoded offline.
//
// The records carry no caller: recording one would cost instructions in
// every task call. The hierarchy is rebuilt from the static call graph in
// DebugTables instead: a task's parent is the deepest active task that can
// call it, directly or through funcs (the first in table order among
// equals). Only a task that two active tasks both can call is ambiguous,
// and then this rule decides, on every target alike (docs/repl.md).
//
// DebugTables are the static half: task names, yield lines, frame fields,
// callers. bsc builds them from the checked behavior; `bsc --instrument`
// also embeds them in the object as JSON (bs_behavior_info.debug_tables)
// so that `bsc trace-decode` needs nothing but the object and the log.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_DEBUG_TRACE_H
#define BSC_DEBUG_TRACE_H

#include "bscript/bscript.h"
#include "llvm/ADT/ArrayRef.h"
#include "llvm/Support/Error.h"
#include "llvm/Support/JSON.h"
#include <string>
#include <vector>

namespace llvm {
class SourceMgr;
class raw_ostream;
} // namespace llvm

namespace bsc {
struct Behavior;
struct BehaviorLayout;

namespace debug {

/// The static description of a behavior the debugger needs.
struct DebugTables {
  struct Field {
    std::string Name;
    std::string Type;
    bool IsParam = false;
  };
  struct Task {
    std::string Name;      ///< `Module::task`.
    std::string ShortName; ///< `task`, or `Module::task` if not unique.
    std::string File;      ///< The file name, without folders.
    unsigned Line = 0;
    /// Line of the k-th yield (resume point k + 1).
    std::vector<unsigned> YieldLines;
    /// The named task state the k-th yield yields (`Done::kicked`, an
    /// `enum ... : TaskState` value), or "" (empty when the tables came
    /// without them).
    std::vector<std::string> YieldStates;
    /// Tasks (by index) that call it directly or through funcs, ascending.
    std::vector<unsigned> Callers;
    std::vector<Field> Fields; ///< Parameters, then locals.
  };
  std::vector<Task> Tasks; ///< In bs_behavior_info.tasks order.
};

/// Builds the tables from a checked behavior (whose Calls give the call
/// graph) and its layout.
DebugTables buildDebugTables(const Behavior &B, const BehaviorLayout &Layout,
                             const llvm::SourceMgr &SM);

/// The JSON form embedded in instrumented objects, and back.
llvm::json::Value toJSON(const DebugTables &T);
llvm::Expected<DebugTables> parseDebugTables(llvm::StringRef JSON);

/// One node of a cycle's hierarchy.
struct ActiveTask {
  bs_activation Record;
  std::vector<unsigned> Children; ///< Indexes into the tree's nodes.
};

/// The hierarchy of one cycle's activations (unknown task ids dropped).
struct ActiveTree {
  std::vector<ActiveTask> Nodes;
  std::vector<unsigned> Roots;
};
ActiveTree buildActiveTree(const DebugTables &T,
                           llvm::ArrayRef<bs_activation> Records);

/// `running, Behavior.bs:57` / `done` / `failure, Kick.bs:9` / `state 3,
/// Head.bs:12` / `Done::kicked, Striker.bs:29`: a task's state (by its
/// name when the yield it waits at yields a named task state) and the yield
/// it waits at.
std::string describeActivation(const DebugTables &T, const bs_activation &A);

/// The hierarchy on one line, each path from a root to a leaf:
/// `play > gotoBallAndKick > executeKick [running, Soccer.bs:57]`, paths
/// separated by `; `; `idle` when no task ran.
std::string formatTraceLine(const DebugTables &T,
                            llvm::ArrayRef<bs_activation> Records);

/// The activations of `State` now (bs_trace_snapshot).
std::vector<bs_activation> takeSnapshot(const void *State,
                                        const bs_behavior_info *Info);

/// A robot's trace log (bscript.h, "Trace logs"): per cycle a header
/// {uint32 cycle, uint32 count} and `count` records, little-endian.
struct LoggedCycle {
  uint32_t Cycle;
  std::vector<bs_activation> Records;
};
llvm::Expected<std::vector<LoggedCycle>> parseTraceLog(llvm::StringRef Bytes,
                                                       size_t NumTasks);

} // namespace debug
} // namespace bsc

#endif
