//===- ReplBreakpoints.cpp - when `:run` stops ----------------------------===//
//
// Breakpoints are checked after each cycle (a cycle is the unit the robot
// runs; the state between cycles is all there is to see), against the
// cycle's activations (bsc/Debug/Trace.h): a task that ran, a task waiting
// at a yield on a line, a task that failed, a watched value that changed;
// `LOC if EXPR` also needs EXPR true after that cycle. `:until EXPR` stops
// the first cycle after which EXPR is true.
//
// Expressions here are probes (ReplProbes.cpp): REPL lines compiled once,
// run under the session's guard after each cycle.
//
//===----------------------------------------------------------------------===//
#include "ReplImpl.h"
#include "llvm/ADT/StringExtras.h"

using namespace bsc;
using namespace bsc::repl;

//===----------------------------------------------------------------------===//
// Checking
//===----------------------------------------------------------------------===//

std::string Repl::checkBreakpoints() {
  std::vector<debug::Activation> Records =
      debug::takeSnapshot(S->getState(), &S->getInfo());
  for (Breakpoint &B : Breakpoints) {
    std::string Hit;
    switch (B.K) {
    case Breakpoint::Task:
      for (const debug::Activation &A : Records)
        if (A.Task == B.TaskIndex) {
          Hit = B.Text + " ran";
          break;
        }
      break;
    case Breakpoint::Line:
      for (const debug::Activation &A : Records) {
        const debug::DebugTables::Task &T = L->Tables.Tasks[A.Task];
        if (A.Resume > 0 && T.File == B.File &&
            T.YieldLines[A.Resume - 1] == B.LineNo) {
          Hit = T.Name + " waits at " + B.Text;
          break;
        }
      }
      break;
    case Breakpoint::Failure:
      for (const debug::Activation &A : Records)
        if (A.State < 0) {
          Hit = L->Tables.Tasks[A.Task].Name + " failed";
          break;
        }
      break;
    case Breakpoint::Watch: {
      std::optional<llvm::json::Value> Now = evalProbe(B.Watched);
      if (!Now)
        return "watch " + std::to_string(B.Number) + " was stopped";
      if (debug::findDifference(B.Last, *Now, B.Text)) {
        const Type *T = B.Watched.Result.Ty;
        std::string Why = "watch " + std::to_string(B.Number) + ", " + B.Text +
                          ": " + formatValue(T, B.Last) + " -> " +
                          formatValue(T, *Now);
        B.Last = std::move(*Now);
        return Why;
      }
      break;
    }
    }
    if (Hit.empty())
      continue;
    if (B.If.Eval && !isTrue(B.If))
      continue;
    return "breakpoint " + std::to_string(B.Number) + ", " + Hit +
           (B.If.Eval ? " and " + B.If.Text + " is true" : "");
  }
  return "";
}

void Repl::rebaseWatches() {
  // A watch stops on what the cycles change, not on what was changed at
  // the prompt since it was last looked at.
  for (Breakpoint &B : Breakpoints)
    if (B.K == Breakpoint::Watch &&
        S->runGuarded(B.Watched.Eval, Opts.CycleLimitMs).K ==
            BehaviorSession::Outcome::Completed)
      B.Last = Values->read(B.Watched.Result.Ty, B.Watched.Result.Ptr);
}

void Repl::destroyBreakpoints() {
  for (Breakpoint &B : Breakpoints) {
    destroyProbe(B.Watched);
    destroyProbe(B.If);
  }
  Breakpoints.clear();
}

//===----------------------------------------------------------------------===//
// Commands
//===----------------------------------------------------------------------===//

/// Splits `LOC if EXPR` at its first ` if `; Cond is empty without one.
static std::pair<llvm::StringRef, llvm::StringRef>
splitCondition(llvm::StringRef Args) {
  for (size_t I = Args.find("if"); I != llvm::StringRef::npos;
       I = Args.find("if", I + 2)) {
    bool WordStart = I > 0 && llvm::isSpace(Args[I - 1]);
    bool WordEnd = I + 2 == Args.size() || llvm::isSpace(Args[I + 2]) ||
                   Args[I + 2] == '(';
    if (WordStart && WordEnd)
      return {Args.take_front(I).rtrim(), Args.drop_front(I + 2).trim()};
  }
  return {Args, ""};
}

void Repl::cmdBreak(llvm::StringRef Args, llvm::SMLoc Loc) {
  if (Args.empty()) {
    C->Diags.report(Loc, diag::err_repl_missing_argument)
        << "break" << "a task, FILE:LINE or 'failure'";
    return;
  }
  auto [Where, Cond] = splitCondition(Args);
  if (Where.size() != Args.size() && Cond.empty()) {
    C->Diags.report(Loc, diag::err_repl_missing_argument)
        << "break ... if" << "a condition";
    return;
  }
  Breakpoint B;
  B.Number = NextBreakpoint;
  B.Text = Where.str();
  if (Where == "failure") {
    B.K = Breakpoint::Failure;
  } else if (auto [File, LineText] = Where.rsplit(':');
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
  } else if (std::optional<unsigned> T = findTask(Where)) {
    B.K = Breakpoint::Task;
    B.TaskIndex = *T;
  } else {
    C->Diags.report(Loc, diag::err_repl_unknown_task) << Where;
    return;
  }
  if (!Cond.empty()) {
    std::optional<Probe> If = compileProbe(Cond, "break", /*Bool=*/true, Loc);
    if (!If)
      return;
    B.If = *If;
  }
  ++NextBreakpoint;
  OS << "breakpoint " << B.Number << ": " << B.Text;
  if (B.If.Eval)
    OS << " if " << B.If.Text;
  OS << "\n";
  Breakpoints.push_back(std::move(B));
}

void Repl::cmdWatch(llvm::StringRef Args, llvm::SMLoc Loc) {
  if (Args.empty()) {
    C->Diags.report(Loc, diag::err_repl_missing_argument)
        << "watch" << "an expression";
    return;
  }
  std::optional<Probe> P = compileProbe(Args, "watch", /*Bool=*/false, Loc);
  if (!P)
    return;
  Breakpoint B;
  B.K = Breakpoint::Watch;
  B.Text = Args.str();
  B.Watched = *P;
  std::optional<llvm::json::Value> Now = evalProbe(B.Watched);
  if (!Now) {
    destroyProbe(B.Watched);
    return;
  }
  B.Number = NextBreakpoint++;
  B.Last = std::move(*Now);
  OS << "watch " << B.Number << ": " << B.Text << " = "
     << formatValue(B.Watched.Result.Ty, B.Last) << "\n";
  Breakpoints.push_back(std::move(B));
}

void Repl::cmdBreaks(llvm::StringRef Args, llvm::SMLoc Loc) {
  if (!noArgs("breaks", Args, Loc))
    return;
  if (Breakpoints.empty())
    OS << "no breakpoints\n";
  for (const Breakpoint &B : Breakpoints) {
    OS << (B.K == Breakpoint::Watch ? "watch " : "breakpoint ") << B.Number
       << ": " << B.Text;
    if (B.If.Eval)
      OS << " if " << B.If.Text;
    OS << "\n";
  }
}

void Repl::cmdDelete(llvm::StringRef Args, llvm::SMLoc Loc) {
  if (Args.empty()) {
    destroyBreakpoints();
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
  destroyProbe(It->Watched);
  destroyProbe(It->If);
  Breakpoints.erase(It);
  OS << "deleted " << Args << "\n";
}

void Repl::cmdUntil(llvm::StringRef Args, llvm::SMLoc Loc) {
  if (Args.empty()) {
    C->Diags.report(Loc, diag::err_repl_missing_argument)
        << "until" << "a condition";
    return;
  }
  auto [Text, CountText] = splitCount(Args);
  unsigned N = parseCount("until", CountText, MaxCycles, Loc);
  if (!N)
    return;
  std::optional<Probe> Until = compileProbe(Text, "until", /*Bool=*/true, Loc);
  if (!Until)
    return;
  if (step(N, /*Report=*/false, &*Until) == StepEnd::Ran)
    OS << Until->Text << " was not true after any of " << N
       << " cycles; stopped after cycle " << S->getCycle() << "\n";
  destroyProbe(*Until);
}
