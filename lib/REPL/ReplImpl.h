//===- ReplImpl.h - the REPL's session, shared by its files ----*- C++ -*-===//
//
// The REPL (Repl.h, docs/repl.md) as one class whose jobs live in their own
// files: Repl.cpp loads the behavior and runs lines of b-script,
// ReplCommands.cpp dispatches the `:` commands and steps cycles,
// ReplBreakpoints.cpp decides when a run stops (breakpoints, watches,
// `:until`), ReplProbes.cpp evaluates their expressions between cycles,
// ReplTime.cpp goes back in time (`:goto`, `:back`, `:history`
// over a CycleHistory), ReplWhy.cpp explains a cycle's conditions.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_LIB_REPL_REPLIMPL_H
#define BSC_LIB_REPL_REPLIMPL_H

#include "bsc/REPL/CycleHistory.h"
#include "bsc/REPL/Repl.h"
#include "bsc/Run/Line.h"
#include "bsc/Sema/Sema.h"
#include "llvm/LineEditor/LineEditor.h"
#include "llvm/Support/raw_ostream.h"
#include <functional>
#include <map>
#include <optional>

namespace bsc {
class DebugSession;
}

namespace bsc::repl {

/// The most cycles one `:step` or `:run` runs: about a day of a robot's
/// 30 Hz cycles would be 2.6 million; a million ends runs that no
/// breakpoint stops, also in batch mode.
constexpr unsigned MaxCycles = 1000000;

/// A compiled expression the REPL evaluates between cycles (a watch, a
/// breakpoint's condition, `:until`, `:history`): the line's function and
/// the slot it writes the value to.
struct Probe {
  std::string Text; ///< As the user wrote it.
  void (*Eval)(void *) = nullptr;
  Slot Result;
};

/// DAP's hit condition (`>= 5`, `== 3`, `% 2`; `5` is `>= 5`): which hits
/// of a breakpoint stop. `:break` has none: every hit stops.
struct HitCondition {
  enum Op { Every, AtLeast, Equal, Greater, Multiple } Operator = Every;
  unsigned N = 0;
  /// Parses `Text`; std::nullopt if it is none of the forms above.
  static std::optional<HitCondition> parse(llvm::StringRef Text);
  bool stopsAt(unsigned Hit) const;
};

/// What a line of b-script evaluated to (no type: a statement).
struct LineValue {
  const Type *Ty = nullptr;
  llvm::json::Value Value = nullptr;
};

struct Breakpoint {
  enum Kind { Task, Line, Code, Failure, Budget, Watch } K;
  unsigned Number;
  std::string Text; ///< As the user wrote it (LOC for `LOC if EXPR`).
  unsigned TaskIndex = 0;
  unsigned LineNo = 0;
  /// Line: the tasks (by index) with a yield on it, found once rather than
  /// by file names after every cycle. Code: the coverage counters of the
  /// statements on the line (a task's header counts its calls).
  std::vector<unsigned> LineTasks, Counters;
  /// Watch: the expression and its last value.
  Probe Watched;
  llvm::json::Value Last = nullptr;
  /// `:break LOC if EXPR`: EXPR, a bool (no Eval: none).
  Probe If;
  /// The debugger's hit condition, and the hits so far (those whose
  /// condition held).
  HitCondition Hits;
  unsigned HitCount = 0;
  /// A logpoint (DAP's logMessage): printed at each hit, never stops. Its
  /// text between the `{expr}`s, and their probes: Log[I] comes before
  /// LogValues[I].
  std::vector<std::string> Log;
  std::vector<Probe> LogValues;
  bool isLogpoint() const { return !Log.empty(); }
};

/// How step() ended.
enum class StepEnd {
  Ran,     ///< Every cycle asked for ran.
  Stopped, ///< A breakpoint, `:until`, the entry's failure or Ctrl-C.
  Broken,  ///< A cycle crashed or ran out of time.
};

/// What ended the last step(), for the debugger (bsc/REPL/DebugSession.h).
struct StopInfo {
  StepEnd End = StepEnd::Ran;
  std::string Why; ///< As "stopped after cycle N: " prints it.
  /// The breakpoints that stopped it, by number.
  std::vector<unsigned> Breakpoints;
  /// Broken: what broke the cycle.
  /// (An assumption that does not hold breaks as an Assertion does.)
  enum Break { None, Assertion, Crash, TimedOut, Diverged } Broke = None;
  bool Assumption = false;
  bool EntryFailed = false, Interrupted = false, Predicate = false;
};

using debug::formatValue;

/// Splits `EXPR [N]` (`:until`, `:history`): a number at the end is N
/// unless the expression needs it (`x == 2` ends in an operand; `x 100`
/// does not). N is empty without one.
std::pair<llvm::StringRef, llvm::StringRef> splitCount(llvm::StringRef Args);

class Repl {
public:
  /// Answers go to `OS`, diagnostics to `Err` (in colour if it is stderr
  /// on a terminal).
  Repl(const ReplOptions &Opts, llvm::raw_ostream &OS,
       llvm::raw_ostream &Err = llvm::errs())
      : Opts(Opts), OS(OS), Err(Err), Frontend(Opts.Frontend) {}
  ~Repl();

  /// Compiles and starts the behavior; false after reporting.
  bool start();
  /// Handles one input line; false once the user quits.
  bool handleLine(llvm::StringRef Line);
  std::vector<llvm::LineEditor::Completion> complete(llvm::StringRef Buffer,
                                                     size_t Pos) const;

private:
  // The debug adapter's face of the session (DebugSession.cpp) drives the
  // same operations as the commands, with structured answers.
  friend class bsc::DebugSession;

  // Loading.
  std::unique_ptr<Compilation> compileFiles();
  bool load(std::unique_ptr<Compilation> NewC);
  /// `:reload`: the world, the frames that still fit, the cycle, input and
  /// output move from the old session to the new one.
  void carryOver(const LoadedBehavior &NewL, BehaviorSession &NewS,
                 debug::ValueIO &NewValues);
  /// The checker of lines, in the frame of `FrameTask` if it has one.
  void makeChecker(llvm::StringRef FrameTask);
  /// First load: `--world-output` and `--world`.
  bool attachWorld();

  // Lines of b-script.
  void evaluate(llvm::StringRef Line);
  /// Runs line `Text` between cycles (a change it makes in the past ends
  /// the history there); its value, or std::nullopt after reporting.
  std::optional<LineValue> runLine(llvm::StringRef Text);
  /// Compiles `Text` as REPL line number ++LineNo (bsc/Run/Line.h); its
  /// result and new variables get slots. Null after reporting.
  std::optional<CompiledLine> compileLine(llvm::StringRef Text);
  void destroySlot(Slot &S);

  // Commands: each takes the text after its name and the place of the line
  // (for carets).
  using Handler = void (Repl::*)(llvm::StringRef Args, llvm::SMLoc Loc);
  struct CommandInfo {
    const char *Name, *Args, *Help;
    Handler Run;
  };
  /// Every command, for dispatch, `:help`, completion and suggestions.
  static llvm::ArrayRef<CommandInfo> getCommands();
  void command(llvm::StringRef Name, llvm::StringRef Args, llvm::SMLoc Loc);
  void cmdStep(llvm::StringRef Args, llvm::SMLoc Loc);
  void cmdRun(llvm::StringRef Args, llvm::SMLoc Loc);
  void cmdTasks(llvm::StringRef Args, llvm::SMLoc Loc);
  void cmdBreak(llvm::StringRef Args, llvm::SMLoc Loc);
  void cmdWatch(llvm::StringRef Args, llvm::SMLoc Loc);
  void cmdBreaks(llvm::StringRef Args, llvm::SMLoc Loc);
  void cmdDelete(llvm::StringRef Args, llvm::SMLoc Loc);
  void cmdReload(llvm::StringRef Args, llvm::SMLoc Loc);
  void cmdRecord(llvm::StringRef Args, llvm::SMLoc Loc);
  void cmdReplay(llvm::StringRef Args, llvm::SMLoc Loc);
  void cmdGraph(llvm::StringRef Args, llvm::SMLoc Loc);
  void cmdCoverage(llvm::StringRef Args, llvm::SMLoc Loc);
  void cmdHelp(llvm::StringRef Args, llvm::SMLoc Loc);
  void cmdWhy(llvm::StringRef Args, llvm::SMLoc Loc); // ReplWhy.cpp
  void cmdFrame(llvm::StringRef Args, llvm::SMLoc Loc);
  void cmdQuiet(llvm::StringRef Args, llvm::SMLoc Loc);
  void cmdRobot(llvm::StringRef Args, llvm::SMLoc Loc);
  /// Reports command `Name` for a team, which it cannot follow (it loads
  /// one behavior into one state: `:reload`, `requires`); true for one
  /// robot.
  bool oneRobot(llvm::StringRef Name, llvm::SMLoc Loc);
  /// Shows robot K: lines, breakpoints, `:why` and the history follow it.
  void selectRobot(unsigned K);
  /// "cycle N" and, for a team, ", robot K".
  std::string cycleName(uint32_t Cycle, unsigned Robot) const;

  // Time travel (ReplTime.cpp).
  void cmdGoto(llvm::StringRef Args, llvm::SMLoc Loc);
  void cmdBack(llvm::StringRef Args, llvm::SMLoc Loc);
  void cmdHistory(llvm::StringRef Args, llvm::SMLoc Loc);
  /// Starts a history per robot at the present cycle (a load, a reload),
  /// or says in NoHistory why the state cannot have one.
  void startHistory();
  static CycleHistory::Blocks getBlocks(const BehaviorSession &R);
  /// Runs the next cycle of every robot in index order (runRobotCycle); at
  /// the first that does not complete, stops with its outcome and index in
  /// `Broke`. `FromHistory`: the cycle was a re-run.
  BehaviorSession::Outcome runNextCycle(bool &FromHistory, unsigned &Broke);
  /// Runs robot K's next cycle: from its history on the logged input (no
  /// world) if the present is in the past, else live, recorded into the
  /// history. A re-run that differs from the live run ends every robot's
  /// history at the cycle before (endHistoryAt).
  BehaviorSession::Outcome runRobotCycle(unsigned K, bool &FromHistory);
  /// Robot K's history->restore, keeping the session's user pointer; the
  /// copy's cycle.
  uint32_t restoreFromHistory(unsigned K, uint32_t Cycle, bool Before);
  /// Puts robot K back as the live run left `Cycle` and forgets the cycles
  /// after it.
  void endHistoryAt(unsigned K, uint32_t Cycle);
  /// A cycle of every robot that ran outside runNextCycle (`:replay`)
  /// enters their histories.
  void recordLiveCycle();
  /// New inputs from here on (`:replay` in the past, a line at the prompt):
  /// every robot's cycles after the present are forgotten, since the world
  /// they share will run them anew.
  void forgetFuture();
  /// With a team, keeps the JIT's log of `:why` for robot K, which the
  /// next robot's cycle overwrites.
  void keepExplainLog(unsigned K);
  /// The state, input and output bytes (empty without a history), to tell
  /// with noteEdits whether a line at the prompt changed them.
  std::vector<unsigned char> copyBlocks() const;
  void noteEdits(const std::vector<unsigned char> &Before);
  /// Goes to cycle `Target` (at most one live run past the history's end);
  /// false after reporting a cycle that crashed on the way.
  bool travelTo(uint32_t Target);
  /// "cycle N: " and its trace line.
  void showCycle();
  /// Report and false without a history, or for a cycle outside it
  /// (`Forward`: any cycle after its start is fine).
  bool checkHistory(llvm::SMLoc Loc);
  bool checkInHistory(long long Cycle, bool Forward, llvm::SMLoc Loc);
  /// `requires "M"` at the prompt: loads M (a :reload with M added to the
  /// inputs) unless it is loaded.
  void requireModule(llvm::StringRef Line, llvm::SMLoc Loc);
  /// Reports arguments given to a command that takes none; true if none.
  bool noArgs(llvm::StringRef Name, llvm::StringRef Args, llvm::SMLoc Loc);
  /// Runs up to N cycles; after each, checks the breakpoints and `Until`
  /// (if given, a bool probe that stops when true).
  /// `StopWhen` (the debugger's step in and out) is asked too; it returns
  /// why to stop, or empty. What ended it is in LastStop.
  StepEnd step(unsigned N, bool Report, Probe *Until = nullptr,
               const std::function<std::string()> &StopWhen = nullptr);
  void cmdUntil(llvm::StringRef Args, llvm::SMLoc Loc);
  /// Compiles `Text` into a probe with a value (of type bool if `Bool`);
  /// reports for command `Cmd` and returns std::nullopt if it has none.
  std::optional<Probe> compileProbe(llvm::StringRef Text, llvm::StringRef Cmd,
                                    bool Bool, llvm::SMLoc Loc);
  /// Runs the probe; its value, or null after reporting a crash or a
  /// runaway loop.
  std::optional<llvm::json::Value> evalProbe(Probe &P);
  /// Whether a bool probe is true now (false if it could not run).
  bool isTrue(Probe &P);
  void destroyProbe(Probe &P) { destroySlot(P.Result); }
  /// Destroys and forgets every breakpoint.
  void destroyBreakpoints();
  /// Parses `:step N`'s N (empty: `Default`); reports and returns 0 if bad.
  unsigned parseCount(llvm::StringRef Cmd, llvm::StringRef Arg,
                      unsigned Default, llvm::SMLoc Loc);

  /// Why the last cycle should stop `:run`, or empty: the shown robot's
  /// breakpoints, or with BreakOnEveryRobot the first robot's that hits
  /// (which is then shown). The numbers that hit go to LastStop.
  std::string checkBreakpoints();
  /// Robot K's breakpoints (watches only for the shown robot). `Counting`:
  /// hits count towards hit conditions and logpoints print (not when
  /// reverse-continue searches the past).
  std::string checkRobotBreakpoints(unsigned K, bool Counting);
  /// A breakpoint at `Where` (TASK, FILE:LINE, failure, budget) numbered
  /// NextBreakpoint, or std::nullopt after reporting why not.
  std::optional<Breakpoint> makeBreakpoint(llvm::StringRef Where,
                                           llvm::SMLoc Loc);
  /// The coverage counters of the statements on `File`:`Line` (a path, or
  /// a file name as `:break` takes it).
  std::vector<unsigned> findLineCounters(llvm::StringRef File,
                                         unsigned Line) const;
  /// Whether the buffer named `BufferName` is `File` (an absolute path, or
  /// the name without folders).
  static bool isFile(llvm::StringRef BufferName, llvm::StringRef File);
  /// The task whose code holds breakpoint B's line (or B's task): the
  /// debugger checks B's condition and log in its frame. Null if none.
  const TaskDecl *getBreakpointTask(const Breakpoint &B) const;
  /// Prints logpoint B's message.
  void printLog(Breakpoint &B);
  /// Destroys breakpoint B's probes.
  void destroyBreakpoint(Breakpoint &B);
  /// Takes the watches' values as the ones to compare against.
  void rebaseWatches();
  /// "stopped after cycle N: why" and the cycle's trace.
  void reportStop(llvm::StringRef Why);
  /// Prints and forgets the diagnostics so far.
  void flushDiagnostics();
  /// Whether diagnostics are in colour (Err is a terminal's stderr).
  bool colors() const;
  /// A buffer holding `Text`, named `<repl>`, for carets under a line.
  llvm::SMLoc addBuffer(llvm::StringRef Text);
  std::optional<unsigned> findTask(llvm::StringRef Name) const;

  const ReplOptions &Opts;
  llvm::raw_ostream &OS, &Err;
  /// Opts.Frontend and the modules `requires` added at the prompt.
  FrontendOptions Frontend;
  /// Per robot (none if NoHistory says why), and the shown robot's: the
  /// robots' cycles are independent given what the histories log, so each
  /// goes back in time through its own.
  std::vector<std::unique_ptr<CycleHistory>> Histories;
  CycleHistory *History = nullptr;
  std::string NoHistory; ///< Why there is no History.
  /// How each cycle that broke live ended, by robot and cycle: a re-run
  /// that cannot break the same way (inside C++) says this instead.
  std::map<std::pair<unsigned, uint32_t>, BehaviorSession::Outcome>
      BrokenOutcomes;
  /// With a team: each robot's copy of the log of `:why` (keepExplainLog).
  std::vector<std::vector<unsigned char>> ExplainLogs;
  /// --world-output's file and `:quiet`'s /dev/null (-1: not open).
  int WorldOutputFd = -1, QuietFd = -1;

  // Declared in the order they must be destroyed in reverse: the session
  // before the JIT that holds its code, both before the compilation whose
  // types and natives they refer to.
  std::unique_ptr<Compilation> C;
  std::unique_ptr<LoadedBehavior> L;
  /// The robots (`--robots N`; one without it) and the one the prompt
  /// shows (`:robot K`): lines, `:tasks`, breakpoints and watches follow it.
  std::unique_ptr<Team> Robots;
  BehaviorSession *S = nullptr;
  unsigned Selected = 0;
  std::unique_ptr<ReplChecker> Checker;
  std::unique_ptr<debug::ValueIO> Values;
  std::vector<Slot> Variables;
  std::vector<Breakpoint> Breakpoints;
  unsigned NextBreakpoint = 1;
  unsigned LineNo = 0;
  std::unique_ptr<llvm::raw_fd_ostream> Recording;
  /// `:record FILE.bslog`: the binary log written into Recording (reset
  /// before it, by stopRecording).
  std::unique_ptr<BinaryLogWriter> RecordingLog;
  /// Ends `:record`: the last block of a binary log, then the file.
  void stopRecording() {
    RecordingLog.reset();
    Recording.reset();
  }
  /// The entry's index in the task table, if the entry is a task (its
  /// failure stops `:run`).
  std::optional<unsigned> EntryIndex;

  // The debugger's (DebugSession.cpp).
  /// Breakpoints stop for whichever robot hits them, not only the shown.
  bool BreakOnEveryRobot = false;
  /// Asked between cycles: true stops a run as Ctrl-C does (DAP's pause).
  std::function<bool()> ShouldPause;
  StopInfo LastStop;
  /// With a Code breakpoint or TrackLines: per robot, the coverage
  /// counters its last cycle advanced (sorted) and that cycle, and the
  /// counters before it.
  bool TrackLines = false;
  std::vector<std::vector<unsigned>> RanCounters;
  std::vector<uint32_t> RanCycle;
  std::vector<uint64_t> CountersBefore;
  bool tracksLines() const;
  /// With a Code breakpoint: the counters before a robot's cycle, and
  /// after it which advanced (RanCounters[K]).
  void markCounters();
  void noteLinesRan(unsigned K);
};

} // namespace bsc::repl

#endif
