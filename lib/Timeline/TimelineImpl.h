//===- TimelineImpl.h - the runs bsc timeline draws ------------*- C++ -*-===//
//
// A run is kept as changes, not as cycles: each leaf of `input` and
// `output` and each task field as the cycles where its value changed, each
// task as segments of consecutive cycles with the same state, yield and
// parent. 100,000 cycles of a behavior whose tasks sit in one state for
// hundreds of cycles shrink to a few thousand entries; the page draws and
// searches them, and comparing two runs walks them (Difference.cpp).
//
// The readers (ReadRun.cpp) hand each cycle to a RunBuilder (RunBuilder.cpp)
// and keep nothing else; Page.cpp writes the result into the page.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_LIB_TIMELINE_TIMELINEIMPL_H
#define BSC_LIB_TIMELINE_TIMELINEIMPL_H

#include "bsc/Timeline/Timeline.h"
#include "llvm/ADT/ArrayRef.h"
#include "llvm/ADT/StringMap.h"
#include "llvm/Support/JSON.h"
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace llvm {
class raw_ostream;
}

namespace bsc {
struct Compilation;
namespace debug {
struct DebugTables;
}

namespace timeline {

/// A value over the cycles: the cycles where it changed, ascending, and
/// the value from each on. Null means absent (a task field while its task
/// is not active).
struct Series {
  std::string Path;
  std::vector<uint32_t> ChangeCycles;
  std::vector<llvm::json::Value> Values;
  /// The value at `Cycle`; null before the first change.
  const llvm::json::Value &at(uint32_t Cycle) const;
};

/// Consecutive cycles in which a task was active with the same state,
/// yield and parent.
struct Segment {
  uint32_t Start, End; ///< Inclusive.
  std::string State;   ///< `running`, `done`, `Done::kicked`, ...
  std::string Place;   ///< `Kick.bs:10`; "" when it finished.
  int Parent;          ///< Index into Run::Tasks; -1 for a root.
};

struct TaskLane {
  std::string Name; ///< `Module::task`.
  std::vector<Segment> Segments;
  /// Its parameters and kept locals; one of a class or array type is its
  /// leaves (`target.x`).
  struct Field {
    std::string Name;
    bool IsParam;
    Series Values;
  };
  std::vector<Field> Fields;
  /// The segment holding `Cycle`, or null.
  const Segment *at(uint32_t Cycle) const;
};

struct Run {
  std::string Name;         ///< The file as given.
  bool FromRobotLog = false; ///< No input, output or fields.
  /// Its robot in a team's file (one run per robot); -1 in one robot's.
  int Robot = -1;
  /// Which file: 0, or 1 of two compared.
  unsigned Record = 0;
  /// The cycles present: inclusive ranges, ascending.
  std::vector<std::pair<uint32_t, uint32_t>> Cycles;
  /// In the order they first ran (depth first within a cycle).
  std::vector<TaskLane> Tasks;
  /// The leaves of `input` and `output` (`input.ball.x`,
  /// `output.wide[6]`), sorted by path.
  std::vector<Series> Leaves;
  bool hasCycle(uint32_t Cycle) const;
  uint32_t numCycles() const;
};

/// One task of a cycle, as a reader found it.
struct CycleTask {
  llvm::StringRef Name, State, Place;
  int Parent = -1; ///< Index into the cycle's tasks, before this one.
  const llvm::json::Object *Params = nullptr, *Locals = nullptr;
};

/// Folds cycles, in increasing order, into a Run: a replay's changes
/// (CycleSink), or whole cycles a reader found (addCycle).
class RunBuilder final : public CycleSink {
public:
  explicit RunBuilder(Run &R) : R(R) {}
  unsigned valueIndex(llvm::StringRef Path) override;
  unsigned laneIndex(llvm::StringRef Task) override;
  unsigned fieldIndex(unsigned Lane, llvm::StringRef Name,
                      bool IsParam) override;
  void beginCycle(uint32_t Cycle) override;
  void setValue(unsigned Value, const llvm::json::Value &V) override;
  void keepValue(unsigned Value) override;
  void addTask(unsigned Lane, llvm::StringRef State, llvm::StringRef Place,
               int ParentLane) override;
  void endCycle() override;
  /// A whole cycle: a recording's line, or a robot's trace (tasks only).
  void addCycle(uint32_t Cycle, const llvm::json::Value *Input,
                const llvm::json::Value *Output,
                llvm::ArrayRef<CycleTask> Tasks);
  /// Sorts the leaves and fields; the run is complete.
  void finish();

private:
  /// A value set whole: `input`, `output` or a part of one (whose leaves
  /// are Run::Leaves), or a task's parameter or local (whose leaves are
  /// its lane's Fields).
  struct Source {
    int Lane; ///< -1 for `input` and `output`.
    bool IsParam;
    std::string Name;
    /// Its leaves, as it was last set.
    std::vector<unsigned> Leaves;
  };
  /// The path of a leaf of `S`: `input.ball.x`, or a field's `target.x`.
  const std::string &leafName(const Source &S, unsigned Leaf) const;
  /// Its index, added if new.
  unsigned findLeaf(const Source &S, llvm::StringRef Leaf);
  void setFields(unsigned Lane, const llvm::json::Object *Fields,
                 bool IsParam);

  Run &R;
  uint32_t Cycle = 0;
  /// Counts the cycles begun: a leaf set or kept in this one has it.
  uint32_t Generation = 0;
  std::vector<Source> Sources;
  llvm::StringMap<unsigned> RootIndex, LaneIndex, LeafIndex;
  /// Per lane: its parameters and locals (Sources), and the leaves of
  /// each (Fields) by name.
  struct LaneKeys {
    llvm::StringMap<unsigned> Params, Locals, ParamLeaves, LocalLeaves;
  };
  std::vector<LaneKeys> Lanes;
  /// Per leaf, and per lane and field, the last generation that set or
  /// kept it: what a cycle did not is absent (null) from then on.
  std::vector<uint32_t> LeafSetIn;
  std::vector<std::vector<uint32_t>> FieldSetIn;
};

/// Sets `V` as the series' value from `Cycle` on, if it differs.
void setValue(Series &S, uint32_t Cycle, const llvm::json::Value &V);

// The readers add a file's runs to `Runs`: one, or one per robot of a
// team's file. They report a file that cannot be read, is not what they
// read, or has a malformed line or record, and return false.

/// Whether the file starts as a recording (JSON text), not a robot's log.
bool isRecording(llvm::StringRef Path);
/// A recording: JSON lines with `tasks` (and `robot` in a team's).
bool readRecording(Compilation &C, llvm::StringRef Path,
                   std::vector<Run> &Runs);
/// The same for a recording already in C.SM, named `Name`.
bool readRecordingBuffer(Compilation &C, unsigned BufferID,
                         llvm::StringRef Name, std::vector<Run> &Runs);
/// A binary log, by replaying it (TimelineOptions::ReplayLog).
bool readReplayedLog(Compilation &C, const TimelineOptions &Opts,
                     llvm::StringRef Path, std::vector<Run> &Runs);
/// A robot's trace log, with the tables of an instrumented object.
bool readRobotLog(Compilation &C, const debug::DebugTables &Tables,
                  llvm::StringRef LogPath, std::vector<Run> &Runs);

/// The first cycle where two runs differ, and each thing that differs in
/// it (`output.motion: A "walk", B "kick"`). A robot's log has only tasks:
/// against it only the tasks compare.
struct Difference {
  uint32_t Cycle;
  std::vector<std::string> Notes;
};
std::optional<Difference> findFirstDifference(const Run &A, const Run &B);
/// The same for two files' runs, robot by robot in teams' (notes name the
/// robot); false after reporting files that cannot compare (a team and one
/// robot, teams of different sizes).
bool compareFiles(Compilation &C, llvm::ArrayRef<Run> A, llvm::ArrayRef<Run> B,
                  std::optional<Difference> &Diff);

/// Writes the page drawing `Runs`.
void writePage(llvm::raw_ostream &OS, llvm::ArrayRef<const Run *> Runs,
               const std::optional<Difference> &Diff);

} // namespace timeline
} // namespace bsc

#endif
