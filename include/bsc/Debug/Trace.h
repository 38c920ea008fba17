//===- Trace.h - which tasks ran in a cycle, and where they stopped -*- C++ -*-===//
//
// A cycle's activation: the tasks called in it, each with the state it left
// and the yield it is suspended at. The JIT's debugger reads it from the
// task headers (a task's last call holds the state's cycle, bit 31 aside;
// bscript.h bs_task_info); a robot
// reads it from the trace record an instrumented behavior writes
// (bscript.h, "Trace records"), which the decoder turns into the same
// activations. So the same lines serve `bsc run --trace`, the REPL's
// `:tasks` and a robot log decoded offline.
//
// The activations carry no caller: recording one would cost instructions
// in every task call. The hierarchy is rebuilt from the static call graph in
// DebugTables instead: a task's parent is the deepest active task that can
// call it, directly or through funcs (the first in table order among
// equals). Only a task that two active tasks both can call is ambiguous,
// and then this rule decides, on every target alike (docs/repl.md).
//
// DebugTables are the static half: task names, yield lines and states,
// frame fields, callers, the trace record's layout. bsc builds them from
// the checked behavior; `bsc --instrument` also embeds them in the object
// as JSON (bs_behavior_info.debug_tables) so that `bsc trace-decode` needs
// nothing but the object and the log.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_DEBUG_TRACE_H
#define BSC_DEBUG_TRACE_H

#include "bscript/bscript.h"
#include "llvm/ADT/ArrayRef.h"
#include "llvm/Support/Error.h"
#include "llvm/Support/JSON.h"
#include <optional>
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
    /// The state the k-th yield leaves, where it is a constant; a yield of
    /// a value computed at run time writes it into the record's StateWord.
    std::vector<std::optional<int32_t>> YieldValues;
    std::optional<uint64_t> StateWord; ///< In the trace record.
    /// Tasks (by index) that call it directly or through funcs, ascending.
    std::vector<unsigned> Callers;
    std::vector<Field> Fields; ///< Parameters, then locals.
  };
  std::vector<Task> Tasks; ///< In bs_behavior_info.tasks order.
  uint64_t RecordSize = 0; ///< Of a trace record (bscript.h).
  unsigned SlotBytes = 1;
  /// `--cycle-budget`: the passes per cycle (0: none), the loops in
  /// bs_budget_layout.loops order, and the trace record's word that names
  /// the loop that ran out in a cycle (1 + its index; 0: none).
  struct Loop {
    std::string Owner; ///< `Module::task` or `Module::func`.
    std::string File;
    unsigned Line = 0;
  };
  uint32_t Budget = 0;
  std::vector<Loop> Loops;
  std::optional<uint64_t> BudgetWord;
};

/// One task that ran in a cycle, and where its last call stopped.
struct Activation {
  unsigned Task = 0;   ///< Index into DebugTables::Tasks.
  unsigned Resume = 0; ///< 0: finished; k: waits after its k-th yield.
  int32_t State = 0;   ///< > 0 running, 0 done, < 0 failure.
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
  Activation Record;
  std::vector<unsigned> Children; ///< Indexes into the tree's nodes.
};

/// The hierarchy of one cycle's activations (unknown task ids dropped).
struct ActiveTree {
  std::vector<ActiveTask> Nodes;
  std::vector<unsigned> Roots;
};
ActiveTree buildActiveTree(const DebugTables &T,
                           llvm::ArrayRef<Activation> Records);

/// `running`, `done`, `failure`, `state 3`, or `Done::kicked` when the
/// yield it waits at yields a named task state.
std::string activationState(const DebugTables &T, const Activation &A);
/// `Behavior.bs:57`, the yield the task waits at; "" when it finished.
std::string activationPlace(const DebugTables &T, const Activation &A);
/// `running, Behavior.bs:57` / `done` / `failure, Kick.bs:9` / `state 3,
/// Head.bs:12` / `Done::kicked, Striker.bs:29`: activationState and
/// activationPlace.
std::string describeActivation(const DebugTables &T, const Activation &A);

/// One task of a cycle as a recording stores it (docs/repl.md, "The
/// JSON-lines format") and the timeline draws it.
struct RecordedTask {
  Activation Record;
  int Parent = -1;   ///< Its parent's position in the list; -1: a root.
  std::string State; ///< activationState.
  std::string Place; ///< activationPlace; "" when it finished.
};
/// The cycle's hierarchy (buildActiveTree) depth first.
std::vector<RecordedTask> listActiveTasks(const DebugTables &T,
                                          llvm::ArrayRef<Activation> Records);

/// listActiveTasks over the cycles of a run, cycle after cycle: where the
/// same tasks are active as in the cycle before, the hierarchy is the one
/// found then, and a task whose activation did not change keeps its state
/// and place, which is most tasks in most cycles (a timeline of 100,000
/// cycles of 42 tasks spent a fifth of its time building them anew).
class ActiveTaskLister {
public:
  explicit ActiveTaskLister(const DebugTables &T) : T(T) {}
  /// listActiveTasks(T, Records).
  const std::vector<RecordedTask> &list(llvm::ArrayRef<Activation> Records);

private:
  const DebugTables &T;
  /// The tasks of the records of the cycle before, in their order.
  std::vector<unsigned> Tasks;
  std::vector<RecordedTask> List;
  /// Per entry of List, its position in the records.
  std::vector<unsigned> RecordOf;
};

/// The hierarchy on one line, each path from a root to a leaf, every task
/// with its describeActivation: `play [running, Soccer.bs:12] >
/// executeKick [done]`, paths separated by `; `; `idle` when no task ran.
/// With `Subtree` (a task's index): only the paths through that task, from
/// it down, each showing what it shares with the path before as `...`
/// (`--trace=TASK`); "not active" when the task is not.
std::string formatTraceLine(const DebugTables &T,
                            llvm::ArrayRef<Activation> Records,
                            std::optional<unsigned> Subtree = std::nullopt);

/// Which cycles a trace prints: every one (`--trace`), or only those whose
/// line differs from the cycle before's (`--trace=changes`): the line
/// spells the hierarchy, the states and the lines, so a change in any of
/// them changes it.
enum class TraceMode { Off, EveryCycle, Changes };

/// Decides, cycle after cycle, whether a trace line is printed.
class TraceFilter {
public:
  explicit TraceFilter(TraceMode Mode) : Mode(Mode) {}
  /// Whether to print `Line`, the next cycle's; the first cycle's always.
  bool shouldPrint(llvm::StringRef Line);

private:
  TraceMode Mode;
  std::optional<std::string> Last;
};

/// The activations of `State` now, read from its frames: the tasks whose
/// last call was in the state's cycle, in task-table order.
std::vector<Activation> takeSnapshot(const void *State,
                                     const bs_behavior_info *Info);

/// The activations a trace record holds (RecordSize bytes); an error names
/// what contradicts the tables.
llvm::Expected<std::vector<Activation>>
decodeTraceRecord(const DebugTables &T, llvm::ArrayRef<uint8_t> Record);

/// A robot's trace log (bscript.h, "Trace logs"): per cycle the uint32
/// cycle and a trace record, little-endian.
struct LoggedCycle {
  uint32_t Cycle;
  std::vector<Activation> Records;
  /// With a cycle budget: 1 + the loop that ran out in this cycle; 0: none.
  uint32_t BudgetLoop = 0;
  /// A team's flight log: the robot (from 0); -1 in one robot's log.
  int Robot = -1;
};
/// One cycle's trace record, decoded as a log's cycle `Cycle` (its
/// activations and budget word).
llvm::Expected<LoggedCycle> decodeLoggedCycle(const DebugTables &T,
                                              uint32_t Cycle,
                                              llvm::ArrayRef<uint8_t> Record);
/// `cycle 7 ran out of its budget of 1000 loop passes in the loop of
/// 'Kick::approach' at Kick.bs:12`: a logged cycle's budget, or "".
std::string formatBudgetLine(const DebugTables &T, const LoggedCycle &C);
llvm::Expected<std::vector<LoggedCycle>> parseTraceLog(llvm::StringRef Bytes,
                                                       const DebugTables &T);

} // namespace debug
} // namespace bsc

#endif
