//===- FailureCause.h - which task a failed replay went astray in -*- C++ -*-===//
//
// `bsc replay` explains a log that failed by replaying it again with the
// conditions recorded (RunOptions::Explain): each cycle, the
// tasks the replay left active are set against those the recording holds
// (a JSON line's `tasks`, a robot log's trace record), and the first task
// that differs is the one whose `:why` the report shows.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_LIB_RUN_FAILURECAUSE_H
#define BSC_LIB_RUN_FAILURECAUSE_H

#include "ReplayReader.h"
#include <optional>
#include <string>
#include <vector>

namespace bsc {

/// A task active in a cycle, as a recording, a robot's trace or a replay
/// has it.
struct ActiveTaskView {
  std::string Name;   ///< `Module::task`.
  std::string State;  ///< `running`, `done`, `Done::kicked`, ...
  std::string Place;  ///< The yield it waits at, `Kick.bs:10`; or "".
  std::string Parent; ///< Its parent's name; "" for a root.
};

/// The tasks the line holds for its cycle; std::nullopt if it holds none
/// (a binary log without trace records) or they cannot be read.
std::optional<std::vector<ActiveTaskView>>
recordedTasks(const LoadedBehavior &L, const ReplayLine &Line);
/// The tasks of a recording's `tasks` text (recordCycle's form: each with
/// `task`, `state`, `parent` and maybe `at`, each task once);
/// std::nullopt for any other.
std::optional<std::vector<ActiveTaskView>>
parseRecordedTasks(llvm::StringRef Text);
/// The tasks `S` left active, in the hierarchy's order.
std::vector<ActiveTaskView> replayedTasks(const LoadedBehavior &L,
                                          const BehaviorSession &S);

/// The first task whose state, yield or parent differs, or that only one
/// side has: in the recording's order, then the replay's.
struct TaskDifference {
  std::string Task;
  std::string Recorded, Replayed; ///< `running at Kick.bs:10 under ...`.
  /// The task whose conditions explain it: the task itself when its
  /// state or yield differs; its caller when one side calls it and the
  /// other does not, or when its caller changed (the caller chose).
  std::string Explains;
};
std::optional<TaskDifference>
findTaskDifference(llvm::ArrayRef<ActiveTaskView> Recorded,
                   llvm::ArrayRef<ActiveTaskView> Replayed);

} // namespace bsc

#endif
