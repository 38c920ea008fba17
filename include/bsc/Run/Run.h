//===- Run.h - running behaviors in the JIT to debug them -------*- C++ -*-===//
//
// The debugging side of bsc (docs/repl.md): `bsc run` with its trace,
// record and replay options, and the pieces the REPL (Repl.h) shares with
// it. Both load a checked behavior into a fresh JIT (loadBehavior) and
// advance a BehaviorSession cycle by cycle; what they print about the
// behavior comes from bsc/Debug (values as JSON, activation traces), so the
// runner, the REPL and a decoded robot log agree word for word.
//
// User mistakes (an unreadable replay file, a runaway cycle, a crash in
// registered C++) are diagnostics in the Compilation's engine; llvm::Errors
// are internal errors.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_RUN_RUN_H
#define BSC_RUN_RUN_H

#include "bsc/CodeGen/CodeGen.h"
#include "bsc/Debug/Trace.h"
#include "bsc/Debug/Values.h"
#include "bsc/Frontend/Frontend.h"
#include "bsc/JIT/JIT.h"
#include "bsc/Run/BinaryLog.h"
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace bsc {
namespace timeline {
class CycleSink;
}

/// The options of loading a behavior into the JIT.
struct LoadOptions {
  unsigned OptLevel = 0;
  /// The files of the standard modules and the --bind objects, as for
  /// FrontendOptions.
  std::vector<std::string> StandardModules, BindObjects;
  /// Funcs and tasks callable by the REPL's lines (CodeGenOptions).
  bool ExternalFunctions = false;
  /// `-g`: DWARF for the behavior, registered with gdb's JIT interface.
  bool DebugInfo = false;
  /// `--cycle-budget=N` (CodeGenOptions::CycleBudget); 0: none.
  uint32_t CycleBudget = 0;
  /// The log of the conditions each cycle evaluated, for the REPL's `:why`
  /// (CodeGenOptions::Explain).
  bool Explain = false;
  /// Counters of what runs, for --coverage and `:coverage`
  /// (CodeGenOptions::Coverage).
  bool Coverage = false;
  /// The debugger's probes (CodeGenOptions::Probes: every local kept in
  /// the state, the site of a crash). `bsc verify` loads without them, so
  /// that the JIT's state has the layout of the code it checks.
  bool Probes = true;
};

/// A behavior compiled into its own JIT, ready for a session.
struct LoadedBehavior {
  std::unique_ptr<BehaviorJIT> JIT;
  BehaviorLayout Layout;
  debug::DebugTables Tables;
  const CallableDecl *Entry = nullptr;
  std::string EntrySymbol;
  /// The world module's input and output classes (null without them).
  const NativeClass *InputClass = nullptr, *OutputClass = nullptr;
  BehaviorJIT::GlobalObject Input, Output;
  /// computeBehaviorHash: recordings name the behavior that made them.
  std::string Hash;
  /// The JIT's log of `:why` (LoadOptions::Explain); null without it.
  ExplainLogHeader *ExplainLog = nullptr;
};

/// Compiles `C.Checked` for the host with debugging probes into a new JIT
/// and links the standard modules and bindings. Returns null after
/// reporting a user error (a binding library the loader refuses, a missing
/// thunk) to C.Diags; an llvm::Error is an internal error.
llvm::Expected<std::unique_ptr<LoadedBehavior>>
loadBehavior(Compilation &C, const CallableDecl &Entry,
             const LoadOptions &Opts);

/// Starts a session; a stale binding module is reported to C.Diags (null
/// result).
llvm::Expected<std::unique_ptr<BehaviorSession>>
startSession(Compilation &C, LoadedBehavior &L);

/// `--robots N` (docs/repl.md "A team in one process"): N sessions of one
/// loaded behavior, each with its own state, input, output and user
/// pointer, and the world library that feeds them. Robots count from 0.
class Team {
public:
  /// Starts `Robots` sessions; null after reporting a stale binding module.
  static llvm::Expected<std::unique_ptr<Team>>
  start(Compilation &C, LoadedBehavior &L, unsigned Robots);
  /// As a robot program ends: a team world's bs_team_exit, then each robot
  /// (its own world's bs_world_exit, its state).
  ~Team();

  unsigned size() const { return Robots.size(); }
  BehaviorSession &operator[](unsigned Robot) const { return *Robots[Robot]; }
  std::vector<BehaviorSession *> getSessions() const;
  /// Starts robots until there are `N` (a team recording to replay); each
  /// gets the team's world and output, told it is robot K of N. False
  /// after reporting.
  bool grow(Compilation &C, LoadedBehavior &L, unsigned N);
  /// Every robot's world prints to `Fd` (BehaviorSession::setWorldOutput).
  void setWorldOutput(int Fd);
  /// `--world LIB.so`: a library that exports bs_team_init is a team world
  /// (bscript/world.h) for all the robots; any other gets one world of its
  /// own per robot (bs_world_init each). False after reporting a library
  /// that cannot be loaded, lacks a required hook, or whose init crashed.
  bool attachWorld(Compilation &C, const LoadedBehavior &L,
                   llvm::StringRef Path, unsigned LimitMs);

private:
  Team() = default;
  std::vector<std::unique_ptr<BehaviorSession>> Robots;
  /// A team world's hooks and bs_team_init's result.
  WorldHooks TeamHooks;
  /// The world attached (team or one-robot hooks) and the output's
  /// descriptor, for robots that join (grow).
  WorldHooks World;
  int WorldOutputFd = -1;
  void *TeamUser = nullptr;
  unsigned LimitMs = 0;
};

/// With more than one robot, a note after a diagnostic about robot
/// `Robot`: which one it was.
void noteRobot(Compilation &C, unsigned Robot, unsigned Robots);

/// How a replay compares recorded outputs (`--ignore`, `--tolerance`):
/// members named by a path of `output` (`output.walkTarget.x`) or any
/// under it; a difference in an ignored member, or in a float member by
/// at most its tolerance, is no difference.
struct OutputComparison {
  std::vector<std::string> Ignore;
  std::vector<std::pair<std::string, double>> Tolerance;
  bool isExact() const { return Ignore.empty() && Tolerance.empty(); }
  /// Whether `D` counts.
  bool counts(const debug::Difference &D) const;
};

/// Where a replay's output first differed from the recording, and how:
/// each member (`output.motion: recorded "walk", got "kick"`).
struct ReplayFailure {
  uint32_t Cycle = 0;
  std::vector<std::string> Differences;
};

/// `bsc run`'s options beyond loading.
struct RunOptions {
  unsigned Cycles = 1;
  bool CyclesGiven = false; ///< --cycles was on the command line.
  /// `--record`: a path with `%r` writes one file per robot (`%r` its
  /// number); otherwise one file, with `robot` on each line of a team.
  std::string RecordPath, ReplayPath;
  /// A replay runs as many robots as the recording's first cycle has
  /// (bsc run without --robots, bsc replay); else the team's size must
  /// match it.
  bool RobotsFromRecording = false;
  debug::TraceMode Trace = debug::TraceMode::Off;
  /// `--trace=TASK`: only that task's subtree (formatTraceLine).
  std::string TraceTask;
  bool PrintOutput = false;
  unsigned CycleLimitMs = 0;
  /// Called after each cycle (the REPL's breakpoints); true stops the run.
  std::function<bool()> StopAfterCycle;
  /// `--regression`: a replay calls registered C++ for real even when the
  /// recording is of this very behavior (docs/repl.md "Recordings").
  bool Regression = false;
  /// Whether a replay says which way it runs (a note); `bsc replay` counts
  /// the ways instead, through ReplayedExactly.
  bool AnnounceReplayMode = true;
  bool *ReplayedExactly = nullptr;
  OutputComparison Compare;
  /// `bsc replay --update`: recorded outputs are not compared but counted
  /// here where they differ (cycles per output member); the run is
  /// recorded again (RecordPath).
  std::map<std::string, unsigned> *Changed = nullptr;
  /// Set to where the replay's output first differed, and how.
  ReplayFailure *Failed = nullptr;
  /// A second look at a replay that failed so (bsc replay's report; the
  /// behavior loaded with LoadOptions::Explain): each cycle's active tasks
  /// are compared with the recording's, and once the output differs as it
  /// did, the first task that differed is noted with `:why` of it in that
  /// cycle (or that the tasks are as recorded); if the output differs
  /// otherwise, a note says so. Outputs are compared but not reported.
  const ReplayFailure *Explain = nullptr;
  /// Each robot's session after each cycle it ran, handed over (`bsc
  /// timeline` of a binary log: TimelineFeed); false stops the run.
  std::function<bool(unsigned Robot, BehaviorSession &S)> TakeCycle;
};

/// `--world-output FILE`: opens FILE (emptied) for what a world library
/// prints (BehaviorSession::setWorldOutput). Returns its descriptor, or -1
/// after reporting a file that cannot be written.
int openWorldOutput(Compilation &C, llvm::StringRef Path);

/// The default --cycle-limit: long enough for any real cycle (a robot's is
/// 10 to 33 ms), short enough that a runaway loop is noticed at once.
constexpr unsigned DefaultCycleLimitMs = 3000;

/// Runs cycles of a session as `bsc run` does. Returns false if it
/// reported an error (a replayed output that differs, a runaway or crashed
/// cycle).
bool runBehavior(Compilation &C, LoadedBehavior &L, BehaviorSession &S,
                 const RunOptions &Opts, llvm::raw_ostream &OS);
/// The same for a team: each cycle runs every robot in index order (and a
/// replay of a team recording may start more robots, Opts'
/// RobotsFromRecording).
bool runTeam(Compilation &C, LoadedBehavior &L, Team &T,
             const RunOptions &Opts, llvm::raw_ostream &OS);

/// The most worker processes `--jobs` takes: far above any machine's
/// cores, low enough that a typo does not fork thousands of processes.
constexpr unsigned MaxReplayJobs = 1024;

/// `bsc replay`'s options beyond loading.
struct ReplayLogsOptions {
  std::string LogsDir;       ///< --logs: the recordings (`*.jsonl`) below it.
  unsigned Shard = 1, Shards = 1; ///< --shard K/N: every N-th log from the K-th.
  std::string JUnitPath;     ///< --junit: JUnit XML, one test case per log.
  /// --jobs: worker processes; 1 replays in this process.
  unsigned Jobs = 1;
  unsigned CycleLimitMs = DefaultCycleLimitMs;
  /// --coverage: the lcov tracefile of all logs together; --fail-under.
  std::string CoveragePath;
  std::optional<double> CoverageFloor;
  /// --world: each log's robots get the library's init and exit (their
  /// user pointers), not its begin and end hooks.
  std::string WorldLibrary;
  bool Regression = false; ///< RunOptions::Regression.
  OutputComparison Compare;
  /// --update: each log is recorded again with the behavior's outputs on
  /// its inputs (open loop), and what changed is summed up per member.
  bool Update = false;
  /// --find EXPR: the stretches of cycles of each log in which EXPR (a
  /// line of b-script of type bool, or a task's name: the task ran) holds,
  /// with the values of its parts; --lasting N: only stretches of N cycles
  /// or more; --first: each log only up to its first.
  std::string Find;
  unsigned FindLasting = 1;
  bool FindFirst = false;
  /// The behavior loaded again with LoadOptions::Explain, once, when a
  /// log first fails (a failure's report names the task that went astray
  /// and shows its `:why`: RunOptions::Explain); null if it
  /// cannot be. Unset: failures are not explained.
  std::function<LoadedBehavior *()> ExplainingBehavior;
};

/// `bsc replay`: replays every recording under Opts.LogsDir against the
/// loaded behavior, each in a fresh session; prints `PASS`/`FAIL` per log
/// (a failure with its diagnostics) and `N passed, M failed`. Returns the
/// exit status: 1 if a log failed or the folder could not be read; an
/// llvm::Error is an internal error.
llvm::Expected<int> replayLogs(Compilation &C, LoadedBehavior &L,
                               const ReplayLogsOptions &Opts,
                               llvm::raw_ostream &OS);

/// `bsc replay --shrink LOG -o OUT`: the shortest recording that fails as
/// the recording or binary log `Log` does (lib/Run/Shrink.cpp), written as
/// JSON lines to `Out`, with the sizes before and after printed to `OS`.
/// Returns the exit status; an llvm::Error is an internal error.
llvm::Expected<int> shrinkLog(Compilation &C, LoadedBehavior &L,
                              const ReplayLogsOptions &Opts,
                              llvm::StringRef Log, llvm::StringRef Out,
                              llvm::raw_ostream &OS);

/// The version of the recordings this bsc writes (docs/repl.md,
/// "Recordings"): 2 adds the header line and each cycle's `calls`.
constexpr unsigned RecordingFormat = 2;

/// The first line of a recording: `{"recording":{"format":2,"behavior":
/// HASH,"entry":NAME}}`.
llvm::json::Value recordHeader(const LoadedBehavior &L);

/// One line of a recording: `{"cycle":N,"input":{...},"output":{...},
/// "tasks":[...]}` for the cycle the session just ran, with its `calls`
/// into registered C++ if the session keeps them (then `input` is the
/// input its entry saw).
llvm::json::Value recordCycle(debug::ValueIO &Values, const LoadedBehavior &L,
                              const BehaviorSession &S);

/// What explainLastCycle could show.
enum class WhyOutcome { Printed, NoCycle, NotRecorded, DidNotRun };

/// `:why`: the conditions the session's last cycle evaluated, from the
/// JIT's explain log (LoadOptions::Explain), with the values of their
/// parts and where each task call ended; of task `Task` (its index in the
/// layout; -1: the entry func's own conditions), or of every task that
/// ran, in the hierarchy's order. NotRecorded if the log is not of that
/// cycle (another cycle ran since, or the behavior was loaded without it).
/// `Copy`: a copy of the JIT's log to read instead (one robot's of a team,
/// whose robots' cycles overwrite each other's).
WhyOutcome explainLastCycle(const LoadedBehavior &L, debug::ValueIO &Values,
                            const BehaviorSession &S, std::optional<int> Task,
                            llvm::raw_ostream &OS,
                            const ExplainLogHeader *Copy = nullptr);

/// Empties the JIT's log of `:why` so that the next entry call starts it
/// afresh. The log keeps what the entry calls of one cycle wrote, and a
/// team's robots run the same cycle one after another.
void startExplainLog(const LoadedBehavior &L);

/// The names a recording gives a task's parameters and locals, in the
/// frame's order (BehaviorLayout::Task::Fields): locals of one name in
/// different blocks are `x`, `x#2`, ...
std::vector<std::string> recordedFieldNames(const BehaviorLayout::Task &T);

/// Hands each cycle a session ran to a timeline (`bsc timeline` of a
/// binary log) as what changed: the values a recording's line would hold
/// (recordCycle), read only where their bytes changed since the cycle
/// before (strings and classes that do not copy as bytes every cycle).
class TimelineFeed {
public:
  TimelineFeed(const LoadedBehavior &L, timeline::CycleSink &Sink);
  void take(const BehaviorSession &S);

private:
  /// A world object: its leaves (`input.ball.x`), each a value of the
  /// sink, and its bytes as last read.
  struct WorldObject {
    const NativeClass *Class = nullptr;
    const char *Name;
    std::vector<std::string> Paths;
    std::vector<unsigned> Leaves;
    std::vector<unsigned char> Bytes;
  };
  void takeObject(WorldObject &O, const void *Bytes, size_t Size);
  /// What the feed knows of a task (by the tables' index).
  struct TaskFeed {
    int Lane = -1; ///< Until the task first runs.
    std::vector<unsigned> Fields; ///< Sink indices, in the frame's order.
    /// Per field, the bytes its value is; 0: more than bytes (a string, a
    /// class that does not copy as bytes), read every cycle.
    std::vector<unsigned> Bytes;
    /// Its frame as last read, in the generation it was active then,
    /// finished or not.
    std::vector<unsigned char> Frame;
    uint32_t ActiveIn = 0;
    bool Finished = false;
  };
  void takeTask(TaskFeed &T, unsigned Task, const char *State,
                bool Finished);

  const LoadedBehavior &L;
  timeline::CycleSink &Sink;
  debug::ValueIO Values;
  debug::ActiveTaskLister Lister;
  WorldObject Input, Output;
  std::vector<TaskFeed> Tasks;
  uint32_t Generation = 0;
};

/// Whether `--record PATH` writes a binary log (bsc/Run/BinaryLog.h)
/// rather than JSON lines: PATH ends in `.bslog`.
bool isBinaryLogPath(llvm::StringRef Path);

/// Whether the binary log `Path` can hold `L`'s world objects as their
/// bytes: a class that owns nothing (trivially destructible, like Eigen's
/// fixed vectors) reads back from them; one that owns memory does not,
/// which is reported at `Loc`.
bool checkWorldAsBytes(DiagnosticEngine &Diags, llvm::SMLoc Loc,
                       const LoadedBehavior &L, llvm::StringRef Path);

/// The header of a binary log that sessions of `L` write on this
/// workstation, for `Robots` robots.
BinaryLogHeader logHeader(const Compilation &C, const LoadedBehavior &L,
                          const BehaviorSession &S, unsigned Robots);

/// Writes the cycle `S` just ran (keeping its calls) into `Log` as robot
/// `Robot`'s.
void logCycle(BinaryLogWriter &Log, unsigned Robot, const LoadedBehavior &L,
              const BehaviorSession &S);

/// `bsc trace-decode` of a flight log (TraceDecodeOptions::ReadFlightLog):
/// each cycle's trace record, every robot's in a team's log. A log without
/// trace records (an object built without --instrument) or a damaged one
/// is reported; std::nullopt then.
std::optional<std::vector<debug::LoggedCycle>>
readFlightLogTraces(llvm::StringRef Path, const debug::DebugTables &Tables,
                    DiagnosticEngine &Diags);

/// `bsc convert`: the recording or binary log `From` written to `To` in
/// the other format (a binary log if `To` ends in `.bslog`), cycle by
/// cycle, without running a cycle; `S` (a session of `L`) lends its
/// objects. False after reporting.
bool convertRecording(Compilation &C, LoadedBehavior &L, BehaviorSession &S,
                      llvm::StringRef From, llvm::StringRef To);

/// A recording's `calls` (recordCycle) into `Into`, for a session of `S`'s
/// sizes. False with `Error` set if they are not of that form.
bool parseRecordedCalls(const llvm::json::Value &Calls,
                        const BehaviorSession &S, CycleRecord &Into,
                        std::string &Error);

/// The JIT's coverage counters now (LoadOptions::Coverage; empty without),
/// one per BehaviorLayout::CoverageSites entry.
std::vector<uint64_t> readCoverage(const LoadedBehavior &L);
/// Sets them to zero.
void clearCoverage(const LoadedBehavior &L);
/// Writes `Counts` (readCoverage's, or their sum over runs) as an lcov
/// tracefile named `TestName`. False after reporting a file that cannot be
/// written.
bool writeLcov(Compilation &C, const LoadedBehavior &L,
               llvm::ArrayRef<uint64_t> Counts, llvm::StringRef Path,
               llvm::StringRef TestName);
/// What counters say a run (or a corpus) exercised.
struct CoverageSummary {
  unsigned Lines = 0, LinesHit = 0, Branches = 0, BranchesHit = 0;
  /// Tasks never called; yields never reached and named states never
  /// yielded (`file:line (Module::task)`).
  std::vector<std::string> NeverActive, YieldsNeverReached, StatesNeverTaken;
  double linePercent() const {
    return Lines ? 100.0 * LinesHit / Lines : 100.0;
  }
};
CoverageSummary summarizeCoverage(Compilation &C, const LoadedBehavior &L,
                                  llvm::ArrayRef<uint64_t> Counts);
/// `coverage: 85.7% of lines (...)` and the three lists.
void printCoverageSummary(llvm::raw_ostream &OS, const CoverageSummary &S);
/// `--fail-under PERCENT`: false after reporting a line coverage below it.
bool checkCoverageFloor(Compilation &C, const CoverageSummary &S,
                        double Floor);

/// After a cycle the guard ended with SIGILL: if an `assert` failed
/// (AssertionMode::Report), reports it at the assertion with the values of
/// its condition's operands, and returns true.
bool reportFailedAssertion(Compilation &C, const LoadedBehavior &L,
                           uint32_t Cycle);

/// The first value where the session's state, input and output differ
/// from `Live` (the three blocks end to end, as a live run left them):
/// "'Striker.x' is 3; the live run left 4". Empty if they are the same.
std::string describeViewDifference(debug::ValueIO &Values,
                                   const LoadedBehavior &L,
                                   const BehaviorSession &S,
                                   llvm::ArrayRef<unsigned char> Live);

/// What ended a cycle early, as a diagnostic (at the loop or the call of
/// registered C++ the probes name). Returns false after reporting.
bool reportOutcome(Compilation &C, const LoadedBehavior &L,
                   const BehaviorSession::Outcome &O, uint32_t Cycle,
                   unsigned LimitMs);

} // namespace bsc

#endif
