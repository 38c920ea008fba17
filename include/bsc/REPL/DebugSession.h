//===- DebugSession.h - the REPL's session for a debug adapter -*- C++ -*-===//
//
// `bsc dap` (lib/DAP) debugs a behavior in an editor over the same session
// as `bsc repl`: the same JIT, cycles, breakpoints, time travel and lines
// of b-script. This is that session with structured answers: where a run
// stopped and why, the active task hierarchy as frames, values as JSON,
// breakpoints by file and line with their verification. Whatever the
// session prints (the REPL's answers, diagnostics) is kept for the
// adapter's debug console (takeOutput, takeErrors).
//
//===----------------------------------------------------------------------===//
#ifndef BSC_REPL_DEBUGSESSION_H
#define BSC_REPL_DEBUGSESSION_H

#include "bsc/REPL/Repl.h"
#include "llvm/Support/JSON.h"
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace bsc {
namespace repl {
class Repl;
struct Breakpoint;
} // namespace repl

/// A task of the active hierarchy (DebugSession::getFrames).
struct DebugFrame {
  std::string Name; ///< `game > striker [running, Game.bs:35]`.
  std::string Path; ///< Its file, absolute.
  unsigned Line = 0;
  /// Its index in the task table; none before a task ran.
  std::optional<unsigned> Task;
  /// Whether it waits at a yield (its locals are kept), and whether it is
  /// running (it did not end with done or failure).
  bool Waiting = false, Running = false;
};

/// A value as the debugger shows it.
struct DebugValue {
  std::string Name;
  std::string Type; ///< `int`, `Game::Input`; empty for a member.
  llvm::json::Value Value = nullptr; ///< As bsc/Debug/Values.h reads it.
  std::string Display;               ///< As the REPL prints it.
  /// An expression for it at the prompt (`input.ball.x`, `striker.state`).
  std::string Path;
};

/// A line breakpoint as the editor sets it.
struct SourceBreakpoint {
  unsigned Line = 0;
  std::string Condition, HitCondition, LogMessage;
};
/// A breakpoint on a task (DAP's function breakpoint).
struct TaskBreakpoint {
  std::string Name, Condition, HitCondition;
};
/// What became of a breakpoint the editor set.
struct BreakpointState {
  bool Verified = false;
  unsigned Id = 0; ///< The REPL's number (`:breaks`, `:delete N`).
  unsigned Line = 0;
  std::string Message; ///< Why it is not verified.
};

/// The run commands: continue, next (one cycle), step in (until the
/// behavior does what it did not in the cycle before: the innermost task
/// waits elsewhere, or a line runs that did not), step out (until the
/// innermost task ends, done or failure, or is no longer active), and back
/// in time.
enum class DebugRun {
  Continue,
  Next,
  StepIn,
  StepOut,
  StepBack,
  ReverseContinue
};

/// Where and why a run stopped.
struct DebugStop {
  enum Reason {
    Step,
    Breakpoint,
    TaskBreakpoint,
    Exception,
    Pause,
    Goto,
    Entry
  } Why = Step;
  std::string Description; ///< `breakpoint 1, striker ran`.
  /// Exception: `assertion`, `taskFailure`, `budget`, `crash`, `timeout`,
  /// `diverged`, and the diagnostics that say what happened.
  std::string ExceptionId, Details;
  std::vector<unsigned> Breakpoints; ///< Those hit.
  unsigned Robot = 0;
};

/// The exception filters (DAP's exceptionBreakpointFilters).
struct ExceptionFilter {
  const char *Id, *Label, *Description;
  bool Default;
};
llvm::ArrayRef<ExceptionFilter> getExceptionFilters();

class DebugSession {
public:
  /// Loads the behavior (a recording or log to replay with `Replay`: its
  /// cycles enter the history and the session goes back to its start).
  /// Null after putting the diagnostics into `Errors`.
  static std::unique_ptr<DebugSession>
  start(const ReplOptions &Opts, llvm::StringRef Replay, std::string &Errors);
  ~DebugSession();

  /// What the session printed, and its diagnostics, since the last call.
  std::string takeOutput();
  std::string takeErrors();

  unsigned getRobots() const;
  uint32_t getCycle() const;

  /// Replaces the line breakpoints of `Path`.
  std::vector<BreakpointState>
  setSourceBreakpoints(llvm::StringRef Path,
                       llvm::ArrayRef<SourceBreakpoint> Breakpoints);
  /// Replaces the breakpoints on tasks.
  std::vector<BreakpointState>
  setTaskBreakpoints(llvm::ArrayRef<TaskBreakpoint> Breakpoints);
  /// Turns on the filters named (getExceptionFilters), the others off; an
  /// unknown one is an error (its message) and changes nothing.
  std::string setExceptionFilters(llvm::ArrayRef<std::string> Filters);

  /// Runs until a stop. `ShouldPause` is asked between cycles.
  DebugStop run(DebugRun How, std::function<bool()> ShouldPause);
  /// Goes to `Cycle` of the history; the stop, or std::nullopt with the
  /// reason in takeErrors().
  std::optional<DebugStop> gotoCycle(uint32_t Cycle);

  /// The tasks of robot `Robot`'s last cycle as `:tasks` lists them (depth
  /// first, siblings in the task table's order), reversed: the last
  /// branch's innermost task first, each task after those it called.
  /// Before the first cycle, the entry.
  std::vector<DebugFrame> getFrames(unsigned Robot) const;
  /// A frame's task's parameters, then the locals it keeps.
  std::vector<DebugValue> getFields(unsigned Robot,
                                    const DebugFrame &Frame) const;
  /// `input` and `output` (none without a world module's classes).
  std::optional<DebugValue> getInput(unsigned Robot) const;
  std::optional<DebugValue> getOutput(unsigned Robot) const;

  /// Evaluates a line of b-script for robot `Robot`, in the frame of
  /// `Task` (its parameters and locals unqualified) if given; the value
  /// (a statement's has no type), or std::nullopt with the diagnostics in
  /// takeErrors().
  std::optional<DebugValue> evaluate(llvm::StringRef Line, unsigned Robot,
                                     std::optional<unsigned> Task);
  /// A line of the debug console: a `:` command or b-script, as at the
  /// REPL's prompt, for robot `Robot`; its answer in takeOutput().
  void runConsoleLine(llvm::StringRef Line, unsigned Robot);
  /// Sets `Path` (a member of `input`) to the b-script expression `Value`;
  /// the new value, or std::nullopt with the reason in takeErrors().
  std::optional<DebugValue> setInput(llvm::StringRef Path,
                                     llvm::StringRef Value, unsigned Robot);
  /// Completions of the console's `Text` at `Pos`.
  std::vector<std::string> complete(llvm::StringRef Text, size_t Pos) const;

private:
  explicit DebugSession(const ReplOptions &Opts);
  DebugStop makeStop(DebugRun How);
  /// `Game.bs:23`: where coverage counter `Counter`'s statement is.
  std::string describeCounter(unsigned Counter) const;
  DebugStop reverseContinue();
  void deleteBreakpoints(std::vector<unsigned> &Numbers);
  /// Gives the breakpoint last added its condition, hit condition and
  /// log, compiled in its task's frame; why it cannot be set, or
  /// std::nullopt.
  std::optional<std::string>
  compileBreakpointParts(llvm::StringRef Condition,
                         llvm::StringRef HitCondition,
                         llvm::StringRef LogMessage);
  /// Adds `B` with those parts: State says its number, or why not.
  bool addBreakpoint(repl::Breakpoint B, llvm::StringRef Condition,
                     llvm::StringRef HitCondition, llvm::StringRef LogMessage,
                     BreakpointState &State);

  ReplOptions Opts;
  std::string Output, Errors;
  std::unique_ptr<llvm::raw_string_ostream> OutputStream, ErrorStream;
  std::unique_ptr<repl::Repl> R;
  /// The REPL's numbers of the breakpoints each file's editor set, of
  /// those on tasks, and of the exception filters'.
  std::map<std::string, std::vector<unsigned>> SourceNumbers;
  std::vector<unsigned> TaskNumbers, FilterNumbers;
  /// The `assertion` filter: a failed assertion stops a run (else it is
  /// reported and the run goes on with the next cycle).
  bool StopOnAssertion = true;
  /// The last cycle of the log replayed at launch, where runs stop.
  std::optional<uint32_t> ReplayEnd;
};

} // namespace bsc

#endif
