//===- Timeline.h - a recorded run as one HTML page ------------*- C++ -*-===//
//
// `bsc timeline RECORD [OTHER] -o run.html` (docs/repl.md, "A run as a
// picture"): reads a recording of `bsc run --record` or the REPL's
// `:record` (whose lines carry each cycle's active tasks), or a robot's
// trace log with the tables of an `--instrument` object, and writes one
// self-contained page that draws it: a lane per task, a cursor over the
// cycles, plots and search. A team's recording (`--robots N`) is drawn as
// a group of lanes per robot under one cursor. Given two recordings, it
// aligns them by cycle (teams robot by robot) and marks the first cycle
// where they differ.
//
// The page's script and markup are lib/Timeline/page/, embedded at build
// time; the data it draws is docs/repl.md's "The timeline's data".
//
//===----------------------------------------------------------------------===//
#ifndef BSC_TIMELINE_TIMELINE_H
#define BSC_TIMELINE_TIMELINE_H

#include "llvm/ADT/StringRef.h"
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace llvm {
class raw_ostream;
namespace json {
class Value;
}
} // namespace llvm

namespace bsc {
struct Compilation;

namespace timeline {

/// A run handed over cycle by cycle as what changed, without text: what a
/// replayed binary log feeds (bsc/Run's TimelineFeed), since turning each
/// of 100,000 cycles of 42 tasks into a recording's line and reading it
/// back took twenty times the replay. Values (`input`, `output`, a task's
/// parameter or local, each drawn as its leaves: `input.ball.x`,
/// `target.x`) and lanes (a task each) are named once, then given by index.
class CycleSink {
public:
  virtual ~CycleSink() = default;
  /// `input` or `output`, or a part of one (`input.ball.x`).
  virtual unsigned valueIndex(llvm::StringRef Path) = 0;
  virtual unsigned laneIndex(llvm::StringRef Task) = 0;
  virtual unsigned fieldIndex(unsigned Lane, llvm::StringRef Name,
                              bool IsParam) = 0;
  /// Starts a cycle, after every earlier one. A value the cycle neither
  /// sets nor keeps is absent in it.
  virtual void beginCycle(uint32_t Cycle) = 0;
  virtual void setValue(unsigned Value, const llvm::json::Value &V) = 0;
  /// The value of the cycle before, unchanged.
  virtual void keepValue(unsigned Value) = 0;
  /// An active task, after its parent's lane (-1 for a root), depth first.
  virtual void addTask(unsigned Lane, llvm::StringRef State,
                       llvm::StringRef Place, int ParentLane) = 0;
  virtual void endCycle() = 0;
};

struct TimelineOptions {
  /// One recording, or two to compare.
  std::vector<std::string> Records;
  /// --object: the records may be robot trace logs (or recordings, to
  /// compare with one), whose tasks this object's tables name.
  std::string ObjectPath;
  /// -o; empty: the first record's name with `.html`.
  std::string OutputPath;
  /// --behavior: the behavior's files, which a binary log (a robot's
  /// flight log, a `.bslog` recording) needs to be read: its bytes are laid
  /// out as the behavior's `input` and `output`, and its tasks are what a
  /// replay computes.
  std::vector<std::string> BehaviorFiles;
  /// --entry, with BehaviorFiles.
  std::string EntryName;
  /// Where a replay hands robot `Robot`'s cycles (of `Robots`, 1 for one
  /// robot's log).
  using SinkForRobot =
      std::function<CycleSink &(unsigned Robot, unsigned Robots)>;
  /// Set by the driver when BehaviorFiles are given: replays the binary
  /// log at the path and hands each robot's cycles to its sink; false
  /// after reporting.
  std::function<bool(llvm::StringRef Path, const SinkForRobot &SinkFor)>
      ReplayLog;
};

/// Writes the page. With two records, prints their first difference (or
/// that they do not differ) to `OS`. Reports unreadable, malformed or
/// mismatched records and unwritable output to C.Diags and returns false.
bool writeTimeline(Compilation &C, const TimelineOptions &Opts,
                   llvm::raw_ostream &OS);

} // namespace timeline
} // namespace bsc

#endif
