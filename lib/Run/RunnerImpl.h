//===- RunnerImpl.h - one `bsc run`, shared by its files --------*- C++ -*-===//
//
// The CycleRunner of runBehavior and runTeam: Runner.cpp opens the replay
// and the recordings and runs the cycles; RunnerCheck.cpp compares what a
// replayed cycle left with what its line recorded, and explains a failure
// (RunOptions::Explain).
//
//===----------------------------------------------------------------------===//
#ifndef BSC_LIB_RUN_RUNNERIMPL_H
#define BSC_LIB_RUN_RUNNERIMPL_H

#include "FailureCause.h"
#include "ReplayReader.h"
#include "llvm/Support/ToolOutputFile.h"

namespace bsc {

/// What a run follows of one robot.
struct RobotRun {
  explicit RobotRun(BehaviorSession *S, debug::TraceMode Mode)
      : S(S), Traces(Mode) {}
  BehaviorSession *S;
  debug::TraceFilter Traces;
  /// `--record` with `%r`: the robot's own file, and its binary log if
  /// it is one.
  std::unique_ptr<llvm::ToolOutputFile> Record;
  std::unique_ptr<BinaryLogWriter> Log;
  bool ReportedFailure = false;
  /// `--cycle-budget`: the first cycle that ran out, and how many did.
  std::optional<std::pair<uint32_t, const bs_loop_info *>> FirstRanOut;
  unsigned RanOut = 0;
};

/// One `bsc run` of one robot or a team: its replay lines and recording
/// files, and what it has seen of each robot so far (the first cycle a
/// budget ran out in, the entry's failure).
class CycleRunner {
public:
  /// `T`, if given, can grow to the size of a team recording.
  CycleRunner(Compilation &C, LoadedBehavior &L, Team *T,
              llvm::ArrayRef<BehaviorSession *> Sessions,
              const RunOptions &Opts, llvm::raw_ostream &OS)
      : C(C), L(L), T(T), Opts(Opts), OS(OS),
        Values([&L](llvm::StringRef Sym) { return L.JIT->lookup(Sym); }) {
    for (BehaviorSession *S : Sessions)
      Robots.emplace_back(S, Opts.Trace);
  }

  /// Opens the replay file and the recordings. False after reporting.
  bool open();
  /// Runs the cycles the options ask for. False after reporting.
  bool run();

private:
  bool openReplay();
  bool openRecordings();
  /// `--cycles N`: every robot N cycles.
  bool runCycles();
  /// Every line of the replay, each robot's in turn.
  bool replay();
  /// Runs one cycle of robot `K`, fed by `Line` if replaying. False after
  /// reporting.
  bool runCycle(unsigned K, const ReplayLine *Line);
  /// The line's input into `S`'s input object. False after reporting.
  bool writeInput(BehaviorSession &S, const ReplayLine &Line);
  /// Whether `S`'s output object holds the line's output; if not, reports
  /// the differences.
  bool checkOutput(BehaviorSession &S, const ReplayLine &Line,
                   uint32_t Cycle);
  /// The same for a binary log's cycle: its bytes, and only where they
  /// differ its members, read as the recording's JSON would be.
  bool checkLoggedOutput(BehaviorSession &S, const BinaryLogCycle &Logged,
                         uint32_t Cycle);
  /// Whether the tasks `S` left active are those of the robot's trace
  /// record in `Logged` (a log of an object built with --instrument); if
  /// not, reports both.
  bool checkLoggedTasks(BehaviorSession &S, const BinaryLogCycle &Logged,
                        uint32_t Cycle);
  /// How `S`'s output differs from the line's, as a failure's notes say
  /// it (--ignore and --tolerance applied), reporting nothing.
  std::vector<std::string> outputDifferences(BehaviorSession &S,
                                             const ReplayLine &Line);
  /// RunOptions::Explain's look at the cycle robot `K` just ran:
  /// true to go on; false once it has noted what it found.
  bool explainFailure(unsigned K, BehaviorSession &S, const ReplayLine &Line,
                      uint32_t Cycle);
  /// The trace line, the output line and the recording of the cycle robot
  /// `K` just ran, each only if asked for.
  void writeCycle(unsigned K, llvm::json::Value Rec,
                  const llvm::json::Value &Out);
  /// Warns once per robot, at the first cycle its entry task ends in
  /// failure.
  void checkEntryFailed(unsigned K, uint32_t Cycle);
  /// `--record`: keeps the files (even after a mismatch, to compare).
  void keepRecordings();
  bool isTeam() const { return Robots.size() > 1; }
  bool recording() const {
    return Record || (!Robots.empty() && Robots[0].Record);
  }

  Compilation &C;
  LoadedBehavior &L;
  Team *T;
  const RunOptions &Opts;
  llvm::raw_ostream &OS;
  debug::ValueIO Values;
  std::vector<RobotRun> Robots;
  std::optional<ReplayReader> Replay;
  /// `--record` without `%r`: every robot's lines, or cycles of a binary
  /// log.
  std::unique_ptr<llvm::ToolOutputFile> Record;
  std::unique_ptr<BinaryLogWriter> Log;
  /// The entry task's place in the task table, whose state tells a failure.
  std::optional<unsigned> EntryIndex;
  /// `--trace=TASK`'s place in the debug tables.
  std::optional<unsigned> TraceSubtree;
  /// A cycle broke off (a crash, a hang, input it could not take): its
  /// recording is not kept.
  bool Broken = false;
  /// The replay takes every call into C++ from the recording (its
  /// behavior is this one), rather than calling the C++.
  bool Exact = false;
  /// RunOptions::Explain: the first cycle whose tasks differed from the
  /// recording's, the difference, and `:why` of the task that explains it.
  struct {
    uint32_t Cycle = 0;
    std::optional<unsigned> Robot;
    TaskDifference Difference;
    std::string Why;
  } FirstTaskDifference;
};

} // namespace bsc

#endif
