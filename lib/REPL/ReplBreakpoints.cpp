//===- ReplBreakpoints.cpp - when `:run` stops ----------------------------===//
//
// Breakpoints are checked after each cycle (a cycle is the unit the robot
// runs; the state between cycles is all there is to see), against the
// cycle's activations (bsc/Debug/Trace.h): a task that ran, a task waiting
// at a yield on a line, a task that failed, a watched value that changed.
//
//===----------------------------------------------------------------------===//
#include "ReplImpl.h"
#include "llvm/ADT/StringExtras.h"

using namespace bsc;
using namespace bsc::repl;

std::string Repl::checkBreakpoints() {
  std::vector<debug::Activation> Records =
      debug::takeSnapshot(S->getState(), &S->getInfo());
  for (Breakpoint &B : Breakpoints) {
    switch (B.K) {
    case Breakpoint::Task:
      for (const debug::Activation &A : Records)
        if (A.Task == B.TaskIndex)
          return "breakpoint " + std::to_string(B.Number) + ", " + B.Text +
                 " ran";
      break;
    case Breakpoint::Line:
      for (const debug::Activation &A : Records) {
        const debug::DebugTables::Task &T = L->Tables.Tasks[A.Task];
        if (A.Resume > 0 && T.File == B.File &&
            T.YieldLines[A.Resume - 1] == B.LineNo)
          return "breakpoint " + std::to_string(B.Number) + ", " + T.Name +
                 " waits at " + B.Text;
      }
      break;
    case Breakpoint::Failure:
      for (const debug::Activation &A : Records)
        if (A.State < 0)
          return "breakpoint " + std::to_string(B.Number) + ", " +
                 L->Tables.Tasks[A.Task].Name + " failed";
      break;
    case Breakpoint::Watch: {
      BehaviorSession::Outcome O = S->runGuarded(B.Eval, Opts.CycleLimitMs);
      if (!reportOutcome(*C, *L, O, S->getCycle(), Opts.CycleLimitMs))
        return "watch " + std::to_string(B.Number) + " was stopped";
      llvm::json::Value Now = Values->read(B.Result.Ty, B.Result.Ptr);
      if (debug::findDifference(B.Last, Now, B.Text)) {
        std::string Why = "watch " + std::to_string(B.Number) + ", " + B.Text +
                          ": " + formatValue(B.Result.Ty, B.Last) + " -> " +
                          formatValue(B.Result.Ty, Now);
        B.Last = std::move(Now);
        return Why;
      }
      break;
    }
    }
  }
  return "";
}

void Repl::rebaseWatches() {
  // A watch stops on what the cycles change, not on what was changed at
  // the prompt since it was last looked at.
  for (Breakpoint &B : Breakpoints)
    if (B.K == Breakpoint::Watch &&
        S->runGuarded(B.Eval, Opts.CycleLimitMs).K ==
            BehaviorSession::Outcome::Completed)
      B.Last = Values->read(B.Result.Ty, B.Result.Ptr);
}

void Repl::cmdBreak(llvm::StringRef Args, llvm::SMLoc Loc) {
  Breakpoint B;
  B.Number = NextBreakpoint;
  B.Text = Args.str();
  if (Args.empty()) {
    C->Diags.report(Loc, diag::err_repl_missing_argument)
        << "break" << "a task, FILE:LINE or 'failure'";
    return;
  }
  if (Args == "failure") {
    B.K = Breakpoint::Failure;
  } else if (auto [File, LineText] = Args.rsplit(':');
             !LineText.empty() && llvm::all_of(LineText, llvm::isDigit)) {
    B.K = Breakpoint::Line;
    B.File = File.str();
    LineText.getAsInteger(10, B.LineNo);
    bool Found = false;
    for (const debug::DebugTables::Task &T : L->Tables.Tasks)
      Found |= T.File == File && llvm::is_contained(T.YieldLines, B.LineNo);
    if (!Found) {
      C->Diags.report(Loc, diag::err_repl_no_yield_at) << File << LineText;
      return;
    }
  } else if (std::optional<unsigned> T = findTask(Args)) {
    B.K = Breakpoint::Task;
    B.TaskIndex = *T;
  } else {
    C->Diags.report(Loc, diag::err_repl_unknown_task) << Args;
    return;
  }
  ++NextBreakpoint;
  OS << "breakpoint " << B.Number << ": " << B.Text << "\n";
  Breakpoints.push_back(std::move(B));
}

void Repl::cmdWatch(llvm::StringRef Args, llvm::SMLoc Loc) {
  if (Args.empty()) {
    C->Diags.report(Loc, diag::err_repl_missing_argument)
        << "watch" << "an expression";
    return;
  }
  std::optional<Compiled> R = compileLine(Args);
  if (!R)
    return;
  if (!R->Result.Ptr) {
    C->Diags.report(Loc, diag::err_repl_watch_void);
    return;
  }
  Breakpoint B;
  B.K = Breakpoint::Watch;
  B.Number = NextBreakpoint++;
  B.Text = Args.str();
  B.Eval = R->Fn;
  B.Result = R->Result;
  BehaviorSession::Outcome O = S->runGuarded(B.Eval, Opts.CycleLimitMs);
  if (!reportOutcome(*C, *L, O, S->getCycle(), Opts.CycleLimitMs)) {
    destroySlot(B.Result);
    return;
  }
  B.Last = Values->read(B.Result.Ty, B.Result.Ptr);
  OS << "watch " << B.Number << ": " << B.Text << " = "
     << formatValue(B.Result.Ty, B.Last) << "\n";
  Breakpoints.push_back(std::move(B));
}

void Repl::cmdBreaks(llvm::StringRef Args, llvm::SMLoc Loc) {
  if (!noArgs("breaks", Args, Loc))
    return;
  if (Breakpoints.empty())
    OS << "no breakpoints\n";
  for (const Breakpoint &B : Breakpoints)
    OS << (B.K == Breakpoint::Watch ? "watch " : "breakpoint ") << B.Number
       << ": " << B.Text << "\n";
}

void Repl::cmdDelete(llvm::StringRef Args, llvm::SMLoc Loc) {
  if (Args.empty()) {
    for (Breakpoint &B : Breakpoints)
      destroySlot(B.Result);
    Breakpoints.clear();
    OS << "deleted every breakpoint\n";
    return;
  }
  unsigned N;
  auto It = Breakpoints.end();
  if (!Args.getAsInteger(10, N))
    It = llvm::find_if(Breakpoints,
                       [&](const Breakpoint &B) { return B.Number == N; });
  if (It == Breakpoints.end()) {
    C->Diags.report(Loc, diag::err_repl_no_breakpoint) << Args;
    return;
  }
  destroySlot(It->Result);
  Breakpoints.erase(It);
  OS << "deleted " << Args << "\n";
}
