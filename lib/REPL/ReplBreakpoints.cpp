//===- ReplBreakpoints.cpp - when `:run` stops ----------------------------===//
//
// Breakpoints are checked after each cycle (a cycle is the unit the robot
// runs; the state between cycles is all there is to see), against the
// cycle's activations (bsc/Debug/Trace.h): a task that ran, a task waiting
// at a yield on a line, a line that ran (its statements' coverage counters
// advanced in the cycle), a task that failed, the cycle budget running
// out, a watched value that changed; `LOC if EXPR` also needs EXPR true
// after that cycle. The debugger adds hit conditions and logpoints
// (DebugSession.cpp). `:until EXPR` stops
// the first cycle after which EXPR is true.
//
// Expressions here are probes (ReplProbes.cpp): REPL lines compiled once,
// run under the session's guard after each cycle.
//
//===----------------------------------------------------------------------===//
#include "ReplImpl.h"
#include "llvm/ADT/ScopeExit.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/Path.h"
#include <algorithm>

using namespace bsc;
using namespace bsc::repl;

//===----------------------------------------------------------------------===//
// Checking
//===----------------------------------------------------------------------===//

std::string Repl::checkBreakpoints() {
  if (!BreakOnEveryRobot)
    return checkRobotBreakpoints(Selected, /*Counting=*/true);
  for (unsigned K = 0; K < Robots->size(); ++K)
    if (std::string Why = checkRobotBreakpoints(K, true); !Why.empty()) {
      selectRobot(K);
      return Why;
    }
  return "";
}

std::string Repl::checkRobotBreakpoints(unsigned K, bool Counting) {
  // Probes (conditions, watches, logpoints) run against the session S.
  BehaviorSession *Shown = S;
  S = &(*Robots)[K];
  auto Restore = llvm::make_scope_exit([&] { S = Shown; });
  std::vector<debug::Activation> Records =
      debug::takeSnapshot(S->getState(), &S->getInfo());
  std::vector<std::string> Hits;
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
        if (A.Resume > 0 && T.YieldLines[A.Resume - 1] == B.LineNo &&
            llvm::is_contained(B.LineTasks, A.Task)) {
          Hit = T.Name + " waits at " + B.Text;
          break;
        }
      }
      break;
    case Breakpoint::Code:
      if (K < RanCounters.size())
        for (unsigned Counter : B.Counters)
          if (std::binary_search(RanCounters[K].begin(), RanCounters[K].end(),
                                 Counter)) {
            Hit = B.Text + " ran";
            break;
          }
      break;
    case Breakpoint::Failure:
      for (const debug::Activation &A : Records)
        if (A.State < 0) {
          Hit = L->Tables.Tasks[A.Task].Name + " failed";
          break;
        }
      break;
    case Breakpoint::Budget:
      if (const bs_loop_info *Loop =
              bs_budget_ran_out(S->getState(), &S->getInfo())) {
        const BehaviorLayout::BudgetLayout::Loop &Where =
            L->Layout.Budget.Loops[Loop - S->getInfo().budget.loops];
        auto [Line, Col] = C->SM.getLineAndColumn(Where.Loc);
        Hit = "the cycle budget ran out in a loop of " +
              Where.Owner->getQualifiedName() + " (line " +
              std::to_string(Line) + ")";
      }
      break;
    case Breakpoint::Watch: {
      if (K != Selected)
        break;
      std::optional<llvm::json::Value> Now = evalProbe(B.Watched);
      if (!Now)
        return "watch " + std::to_string(B.Number) + " was stopped";
      if (debug::findDifference(B.Last, *Now, B.Text)) {
        const Type *T = B.Watched.Result.Ty;
        std::string Why = "watch " + std::to_string(B.Number) + ", " + B.Text +
                          ": " + formatValue(T, B.Last) + " -> " +
                          formatValue(T, *Now);
        B.Last = std::move(*Now);
        LastStop.Breakpoints.push_back(B.Number);
        return Why;
      }
      break;
    }
    }
    if (Hit.empty())
      continue;
    if (B.If.Eval && !isTrue(B.If))
      continue;
    if (Counting) {
      if (!B.Hits.stopsAt(++B.HitCount))
        continue;
      if (B.isLogpoint()) {
        printLog(B);
        continue;
      }
    } else if (B.isLogpoint()) {
      continue;
    }
    Hits.push_back("breakpoint " + std::to_string(B.Number) + ", " + Hit +
                   (B.If.Eval ? " and " + B.If.Text + " is true" : ""));
    LastStop.Breakpoints.push_back(B.Number);
  }
  // Every breakpoint hit counts, though the first names the stop.
  return Hits.empty() ? "" : Hits.front();
}

void Repl::printLog(Breakpoint &B) {
  std::string Message;
  for (size_t I = 0; I < B.Log.size(); ++I) {
    Message += B.Log[I];
    if (I < B.LogValues.size()) {
      std::optional<llvm::json::Value> V = evalProbe(B.LogValues[I]);
      Message += V ? formatValue(B.LogValues[I].Result.Ty, *V) : "<stopped>";
    }
  }
  flushDiagnostics();
  OS << Message << "\n";
}

std::optional<HitCondition> HitCondition::parse(llvm::StringRef Text) {
  Text = Text.trim();
  HitCondition H;
  H.Operator = AtLeast;
  for (auto [Spelling, Op] : {std::pair{">=", AtLeast}, {"==", Equal},
                              {">", Greater}, {"%", Multiple}})
    if (Text.consume_front(Spelling)) {
      H.Operator = Op;
      break;
    }
  Text = Text.trim();
  if (Text.empty() || !llvm::all_of(Text, llvm::isDigit) ||
      Text.getAsInteger(10, H.N) || (H.Operator == Multiple && H.N == 0))
    return std::nullopt;
  return H;
}

bool HitCondition::stopsAt(unsigned Hit) const {
  switch (Operator) {
  case Every:
    return true;
  case AtLeast:
    return Hit >= N;
  case Equal:
    return Hit == N;
  case Greater:
    return Hit > N;
  case Multiple:
    return Hit % N == 0;
  }
  return true;
}

const TaskDecl *Repl::getBreakpointTask(const Breakpoint &B) const {
  switch (B.K) {
  case Breakpoint::Task:
    return llvm::dyn_cast<TaskDecl>(L->Layout.Tasks[B.TaskIndex].Decl);
  case Breakpoint::Code:
    return llvm::dyn_cast<TaskDecl>(
        L->Layout.CoverageSites[B.Counters.front()].Owner);
  case Breakpoint::Line:
    return llvm::dyn_cast<TaskDecl>(
        L->Layout.Tasks[B.LineTasks.front()].Decl);
  default:
    return nullptr;
  }
}

bool Repl::tracksLines() const {
  return TrackLines || llvm::any_of(Breakpoints,
                      [](const Breakpoint &B) { return B.K == Breakpoint::Code; });
}

bool Repl::isFile(llvm::StringRef BufferName, llvm::StringRef File) {
  if (!llvm::sys::path::is_absolute(File))
    return llvm::sys::path::filename(BufferName) == File || BufferName == File;
  llvm::SmallString<256> A(BufferName), B(File);
  llvm::sys::fs::make_absolute(A);
  llvm::sys::path::remove_dots(A, /*remove_dot_dot=*/true);
  llvm::sys::path::remove_dots(B, /*remove_dot_dot=*/true);
  if (A == B)
    return true;
  llvm::SmallString<256> RealA, RealB;
  return !llvm::sys::fs::real_path(A, RealA) &&
         !llvm::sys::fs::real_path(B, RealB) && RealA == RealB;
}

std::vector<unsigned> Repl::findLineCounters(llvm::StringRef File,
                                             unsigned Line) const {
  std::vector<unsigned> Counters;
  const std::vector<CoverageSite> &Sites = L->Layout.CoverageSites;
  for (unsigned I = 0; I < Sites.size(); ++I) {
    if (Sites[I].Kind != CoverageSite::Stmt &&
        Sites[I].Kind != CoverageSite::Call)
      continue;
    unsigned Buffer = C->SM.FindBufferContainingLoc(Sites[I].N->getLoc());
    if (Buffer &&
        C->SM.FindLineNumber(Sites[I].N->getLoc(), Buffer) == Line &&
        isFile(C->SM.getMemoryBuffer(Buffer)->getBufferIdentifier(), File))
      Counters.push_back(I);
  }
  return Counters;
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

void Repl::destroyBreakpoint(Breakpoint &B) {
  destroyProbe(B.Watched);
  destroyProbe(B.If);
  for (Probe &P : B.LogValues)
    destroyProbe(P);
}

void Repl::destroyBreakpoints() {
  for (Breakpoint &B : Breakpoints)
    destroyBreakpoint(B);
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

std::optional<Breakpoint> Repl::makeBreakpoint(llvm::StringRef Where,
                                               llvm::SMLoc Loc) {
  Breakpoint B;
  B.Number = NextBreakpoint;
  B.Text = Where.str();
  if (Where == "failure") {
    B.K = Breakpoint::Failure;
  } else if (Where == "budget") {
    B.K = Breakpoint::Budget;
  } else if (auto [File, LineText] = Where.rsplit(':');
             !LineText.empty() && llvm::all_of(LineText, llvm::isDigit)) {
    LineText.getAsInteger(10, B.LineNo);
    // A yield's line stops where a task waits; another line with code
    // stops after a cycle that ran it.
    B.K = Breakpoint::Line;
    for (unsigned I = 0; I < L->Layout.Tasks.size(); ++I) {
      unsigned Buffer =
          C->SM.FindBufferContainingLoc(L->Layout.Tasks[I].Decl->getLoc());
      if (Buffer &&
          llvm::is_contained(L->Tables.Tasks[I].YieldLines, B.LineNo) &&
          isFile(C->SM.getMemoryBuffer(Buffer)->getBufferIdentifier(), File))
        B.LineTasks.push_back(I);
    }
    if (B.LineTasks.empty()) {
      B.K = Breakpoint::Code;
      B.Counters = findLineCounters(File, B.LineNo);
      if (B.Counters.empty()) {
        C->Diags.report(Loc, diag::err_repl_no_code_at) << File << LineText;
        return std::nullopt;
      }
    }
  } else if (std::optional<unsigned> T = findTask(Where)) {
    B.K = Breakpoint::Task;
    B.TaskIndex = *T;
  } else {
    C->Diags.report(Loc, diag::err_repl_unknown_task) << Where;
    return std::nullopt;
  }
  return B;
}

void Repl::cmdBreak(llvm::StringRef Args, llvm::SMLoc Loc) {
  if (Args.empty()) {
    C->Diags.report(Loc, diag::err_repl_missing_argument)
        << "break" << "a task, FILE:LINE, 'failure' or 'budget'";
    return;
  }
  auto [Where, Cond] = splitCondition(Args);
  if (Where.size() != Args.size() && Cond.empty()) {
    C->Diags.report(Loc, diag::err_repl_missing_argument)
        << "break ... if" << "a condition";
    return;
  }
  std::optional<Breakpoint> B = makeBreakpoint(Where, Loc);
  if (!B)
    return;
  if (!Cond.empty()) {
    std::optional<Probe> If = compileProbe(Cond, "break", /*Bool=*/true, Loc);
    if (!If)
      return;
    B->If = *If;
  }
  ++NextBreakpoint;
  OS << "breakpoint " << B->Number << ": " << B->Text;
  if (B->If.Eval)
    OS << " if " << B->If.Text;
  OS << "\n";
  Breakpoints.push_back(std::move(*B));
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
  destroyBreakpoint(*It);
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
