//===- DebugSession.cpp - the REPL's session for a debug adapter ----------===//
//
// Every operation goes through the REPL's own (ReplImpl.h): breakpoints
// are the REPL's, numbered as `:breaks` lists them, with the debugger's
// hit conditions and logpoints; runs are step(), time travel is travelTo();
// values are read as `:tasks` reads them. A behavior's state exists only
// between cycles, so the debugger stops after a cycle (that ran a line,
// or left a task waiting at a yield on it), and stepping is by cycles:
//
//   next       one cycle
//   step in    cycles until the behavior does what it did not in the
//              cycle before: the innermost active task waits elsewhere
//              (another line, another task), or a line runs that did not
//              (the statements' coverage counters say which ran)
//   step out   cycles until that task ends (done or failure) or is no
//              longer active
//   step back  one cycle back in time; reverse continue goes back to the
//              last earlier cycle at which a breakpoint would have stopped
//
//===----------------------------------------------------------------------===//
#include "bsc/REPL/DebugSession.h"
#include "ReplImpl.h"
#include "llvm/ADT/ScopeExit.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/Path.h"
#include <algorithm>

using namespace bsc;
using namespace bsc::repl;

llvm::ArrayRef<ExceptionFilter> bsc::getExceptionFilters() {
  static const ExceptionFilter Filters[] = {
      {"assertion", "Failed assertions",
       "Stop in the cycle whose assert failed or assume did not hold (else "
       "it is reported and the run goes on)",
       true},
      {"taskFailure", "Task failures",
       "Stop after a cycle in which a task failed", false},
      {"budget", "Cycle budget ran out",
       "Stop after a cycle in which a loop ran out of --cycle-budget's "
       "passes",
       true},
  };
  return Filters;
}

DebugSession::DebugSession(const ReplOptions &Opts) : Opts(Opts) {
  OutputStream = std::make_unique<llvm::raw_string_ostream>(Output);
  ErrorStream = std::make_unique<llvm::raw_string_ostream>(Errors);
  R = std::make_unique<Repl>(this->Opts, *OutputStream, *ErrorStream);
}

DebugSession::~DebugSession() = default;

std::unique_ptr<DebugSession> DebugSession::start(const ReplOptions &Opts,
                                                  llvm::StringRef Replay,
                                                  std::string &Errors) {
  std::unique_ptr<DebugSession> D(new DebugSession(Opts));
  auto Fail = [&] {
    Errors = D->takeErrors() + D->takeOutput();
    return nullptr;
  };
  if (!D->R->start())
    return Fail();
  D->R->BreakOnEveryRobot = true;
  D->R->TrackLines = true; // Step in compares the lines of cycles.
  std::vector<std::string> Defaults;
  for (const ExceptionFilter &F : getExceptionFilters())
    if (F.Default)
      Defaults.push_back(F.Id);
  D->setExceptionFilters(Defaults);
  if (!Replay.empty()) {
    // Its cycles enter the history; the editor then starts at its start.
    std::string Line = ":replay " + Replay.str();
    D->R->cmdReplay(Replay, D->R->addBuffer(Line));
    D->R->flushDiagnostics();
    if (D->getCycle() == 0)
      return Fail();
    D->ReplayEnd = D->getCycle();
    if (D->R->History)
      D->R->travelTo(D->R->History->first());
  }
  return D;
}

std::string DebugSession::takeOutput() {
  OutputStream->flush();
  return std::exchange(Output, "");
}

std::string DebugSession::takeErrors() {
  R->flushDiagnostics();
  ErrorStream->flush();
  return std::exchange(Errors, "");
}

unsigned DebugSession::getRobots() const { return R->Robots->size(); }
uint32_t DebugSession::getCycle() const { return R->S->getCycle(); }

//===----------------------------------------------------------------------===//
// Breakpoints
//===----------------------------------------------------------------------===//

void DebugSession::deleteBreakpoints(std::vector<unsigned> &Numbers) {
  for (unsigned N : Numbers) {
    auto It = llvm::find_if(R->Breakpoints,
                            [&](const Breakpoint &B) { return B.Number == N; });
    if (It == R->Breakpoints.end())
      continue; // `:delete` in the console took it.
    R->destroyBreakpoint(*It);
    R->Breakpoints.erase(It);
  }
  Numbers.clear();
}

/// Splits a logpoint's message at its `{expr}`s: the texts around them and
/// the expressions; false if a brace is not closed.
static bool splitLogMessage(llvm::StringRef Message,
                            std::vector<std::string> &Texts,
                            std::vector<std::string> &Exprs) {
  std::string Text;
  while (!Message.empty()) {
    size_t Open = Message.find('{');
    if (Open == llvm::StringRef::npos)
      break;
    size_t Close = Message.find('}', Open);
    if (Close == llvm::StringRef::npos)
      return false;
    Texts.push_back(Text + Message.take_front(Open).str());
    Text.clear();
    Exprs.push_back(Message.slice(Open + 1, Close).trim().str());
    Message = Message.drop_front(Close + 1);
  }
  Texts.push_back(Text + Message.str());
  return true;
}

std::optional<std::string>
DebugSession::compileBreakpointParts(llvm::StringRef Condition,
                                     llvm::StringRef HitCondition,
                                     llvm::StringRef LogMessage) {
  Breakpoint &B = R->Breakpoints.back();
  // The condition and the log see the task's parameters and locals
  // unqualified, as its code does.
  const TaskDecl *Frame = R->Checker->getFrame();
  R->Checker->setFrame(R->getBreakpointTask(B));
  auto RestoreFrame =
      llvm::make_scope_exit([&] { R->Checker->setFrame(Frame); });
  if (!HitCondition.trim().empty()) {
    std::optional<repl::HitCondition> H =
        repl::HitCondition::parse(HitCondition);
    if (!H)
      return "a hit count is a number after '>=', '==', '>' or '%' (a "
             "number alone: '>='), not '" +
             HitCondition.str() + "'";
    B.Hits = *H;
  }
  if (!Condition.trim().empty()) {
    std::optional<Probe> If = R->compileProbe(Condition, "break", /*Bool=*/true,
                                              R->addBuffer(Condition));
    if (!If)
      return takeErrors();
    B.If = *If;
  }
  if (!LogMessage.empty()) {
    std::vector<std::string> Texts, Exprs;
    if (!splitLogMessage(LogMessage, Texts, Exprs))
      return std::string("a '{' in the log message is not closed");
    for (const std::string &E : Exprs) {
      std::optional<Probe> P =
          R->compileProbe(E, "log", /*Bool=*/false, R->addBuffer(E));
      if (!P)
        return takeErrors();
      B.LogValues.push_back(*P);
    }
    B.Log = Texts;
  }
  return std::nullopt;
}

bool DebugSession::addBreakpoint(Breakpoint B, llvm::StringRef Condition,
                                 llvm::StringRef HitCondition,
                                 llvm::StringRef LogMessage,
                                 BreakpointState &State) {
  unsigned Number = B.Number;
  R->Breakpoints.push_back(std::move(B));
  if (std::optional<std::string> Why =
          compileBreakpointParts(Condition, HitCondition, LogMessage)) {
    R->destroyBreakpoint(R->Breakpoints.back());
    R->Breakpoints.pop_back();
    State.Message = *Why;
    return false;
  }
  ++R->NextBreakpoint;
  State.Verified = true;
  State.Id = Number;
  return true;
}

std::vector<BreakpointState>
DebugSession::setSourceBreakpoints(llvm::StringRef Path,
                                   llvm::ArrayRef<SourceBreakpoint> Wanted) {
  std::vector<unsigned> &Numbers = SourceNumbers[Path.str()];
  deleteBreakpoints(Numbers);
  std::vector<BreakpointState> States;
  for (const SourceBreakpoint &SB : Wanted) {
    BreakpointState State;
    State.Line = SB.Line;
    std::string Where = Path.str() + ":" + std::to_string(SB.Line);
    std::optional<Breakpoint> B = R->makeBreakpoint(Where, R->addBuffer(Where));
    if (!B) {
      R->C->Diags.clear();
      State.Message = "nothing runs on line " + std::to_string(SB.Line) +
                      ": a breakpoint needs a statement, a yield or a "
                      "task's first line";
      States.push_back(State);
      continue;
    }
    B->Text =
        llvm::sys::path::filename(Path).str() + ":" + std::to_string(SB.Line);
    if (addBreakpoint(std::move(*B), SB.Condition, SB.HitCondition,
                      SB.LogMessage, State))
      Numbers.push_back(State.Id);
    States.push_back(State);
  }
  return States;
}

std::vector<BreakpointState>
DebugSession::setTaskBreakpoints(llvm::ArrayRef<TaskBreakpoint> Wanted) {
  deleteBreakpoints(TaskNumbers);
  std::vector<BreakpointState> States;
  for (const TaskBreakpoint &TB : Wanted) {
    BreakpointState State;
    std::optional<unsigned> Task = R->findTask(TB.Name);
    if (!Task) {
      State.Message = "no task '" + TB.Name + "' in the behavior";
      States.push_back(State);
      continue;
    }
    std::optional<Breakpoint> B =
        R->makeBreakpoint(TB.Name, R->addBuffer(TB.Name));
    if (addBreakpoint(std::move(*B), TB.Condition, TB.HitCondition, "",
                      State)) {
      TaskNumbers.push_back(State.Id);
      State.Line = R->L->Tables.Tasks[*Task].Line;
    }
    States.push_back(State);
  }
  return States;
}

std::string
DebugSession::setExceptionFilters(llvm::ArrayRef<std::string> Filters) {
  for (const std::string &F : Filters)
    if (!llvm::any_of(getExceptionFilters(),
                      [&](const ExceptionFilter &E) { return F == E.Id; }))
      return "no exception filter '" + F + "' (assertion, taskFailure, budget)";
  deleteBreakpoints(FilterNumbers);
  StopOnAssertion = llvm::is_contained(Filters, "assertion");
  // The budget first: a loop that runs out of it fails its task too, and
  // the first breakpoint hit names the stop.
  for (llvm::StringRef Where : {"budget", "failure"}) {
    if (!llvm::is_contained(Filters,
                            Where == "failure" ? "taskFailure" : "budget"))
      continue;
    std::optional<Breakpoint> B = R->makeBreakpoint(Where, llvm::SMLoc());
    FilterNumbers.push_back(R->NextBreakpoint++);
    R->Breakpoints.push_back(std::move(*B));
  }
  return "";
}

//===----------------------------------------------------------------------===//
// Running
//===----------------------------------------------------------------------===//

std::string DebugSession::describeCounter(unsigned Counter) const {
  const CoverageSite &Site = R->L->Layout.CoverageSites[Counter];
  unsigned Buffer = R->C->SM.FindBufferContainingLoc(Site.N->getLoc());
  if (!Buffer)
    return Site.Owner->getQualifiedName();
  return llvm::sys::path::filename(
             R->C->SM.getMemoryBuffer(Buffer)->getBufferIdentifier())
             .str() +
         ":" +
         std::to_string(R->C->SM.FindLineNumber(Site.N->getLoc(), Buffer));
}

/// Where the innermost active task of `Frames` waits: (task, line), or
/// none.
static std::optional<std::pair<unsigned, unsigned>>
innermostPlace(const std::vector<DebugFrame> &Frames) {
  if (Frames.empty() || !Frames.front().Task)
    return std::nullopt;
  return std::pair{*Frames.front().Task, Frames.front().Line};
}

DebugStop DebugSession::run(DebugRun How, std::function<bool()> ShouldPause) {
  // A replayed log's runs stop at its end: past it the behavior runs live,
  // on no logged input, which the next run does if asked.
  unsigned Limit = MaxCycles;
  if (ReplayEnd && getCycle() < *ReplayEnd)
    Limit = *ReplayEnd - getCycle();
  auto AtLogEnd = [&](DebugStop Stop) {
    if (ReplayEnd && getCycle() == *ReplayEnd &&
        R->LastStop.End == StepEnd::Ran && How != DebugRun::Next) {
      Stop.Why = DebugStop::Pause;
      Stop.Description = "the end of the replayed log, cycle " +
                         std::to_string(*ReplayEnd) +
                         " (from here the behavior runs live)";
      *OutputStream << Stop.Description << "\n";
    }
    return Stop;
  };
  R->ShouldPause = std::move(ShouldPause);
  auto Done = llvm::make_scope_exit([&] { R->ShouldPause = nullptr; });
  switch (How) {
  case DebugRun::StepBack: {
    R->cmdBack("", R->addBuffer(":back"));
    R->flushDiagnostics();
    DebugStop Stop;
    Stop.Robot = R->Selected;
    Stop.Description = "cycle " + std::to_string(getCycle());
    return Stop;
  }
  case DebugRun::ReverseContinue:
    return reverseContinue();
  case DebugRun::Next:
    R->step(1, /*Report=*/true);
    return makeStop(How);
  case DebugRun::StepIn: {
    // Until the behavior does what it did not in the cycle before: a task
    // waits elsewhere, or a line runs that did not (a branch turned).
    unsigned K = R->Selected;
    auto Before = innermostPlace(getFrames(K));
    std::optional<std::vector<unsigned>> Lines;
    if (K < R->RanCycle.size() && R->RanCycle[K] == getCycle())
      Lines = R->RanCounters[K];
    R->step(Limit, false, nullptr, [&]() -> std::string {
      std::vector<DebugFrame> Frames = getFrames(K);
      if (innermostPlace(Frames) != Before)
        return Frames.front().Name + " is the innermost task";
      std::optional<std::vector<unsigned>> Previous = std::move(Lines);
      Lines = R->RanCounters[K];
      const std::vector<CoverageSite> &Sites = R->L->Layout.CoverageSites;
      for (unsigned Counter : Previous ? *Lines : std::vector<unsigned>())
        if (Sites[Counter].Kind != CoverageSite::True &&
            Sites[Counter].Kind != CoverageSite::False &&
            !std::binary_search(Previous->begin(), Previous->end(), Counter))
          return describeCounter(Counter) + " ran, which it did not in cycle " +
                 std::to_string(getCycle() - 1);
      return "";
    });
    return AtLogEnd(makeStop(How));
  }
  case DebugRun::StepOut: {
    unsigned K = R->Selected;
    std::vector<DebugFrame> Frames = getFrames(K);
    std::optional<unsigned> Task =
        Frames.empty() ? std::nullopt : Frames.front().Task;
    if (!Task) { // Nothing to step out of: one cycle.
      R->step(1, true);
      return makeStop(How);
    }
    std::string Name = R->L->Tables.Tasks[*Task].ShortName;
    R->step(Limit, false, nullptr, [&]() -> std::string {
      for (const DebugFrame &F : getFrames(K))
        if (F.Task == Task)
          return F.Running ? "" : F.Name;
      return Name + " is no longer active";
    });
    return AtLogEnd(makeStop(How));
  }
  case DebugRun::Continue:
    break;
  }
  // A failed assertion ends a cycle; without the filter the run goes on,
  // within the same number of cycles, and a pause stops it there too.
  uint32_t Start = getCycle();
  while (true) {
    R->step(Limit - std::min(Limit, getCycle() - Start), /*Report=*/false);
    if (R->LastStop.End != StepEnd::Broken ||
        R->LastStop.Broke != StopInfo::Assertion || StopOnAssertion)
      return AtLogEnd(makeStop(How));
    if (getCycle() - Start >= Limit)
      return AtLogEnd(makeStop(How));
    if (R->ShouldPause && R->ShouldPause()) {
      DebugStop Stop;
      Stop.Why = DebugStop::Pause;
      Stop.Robot = R->Selected;
      Stop.Description = "paused at cycle " + std::to_string(getCycle());
      return Stop;
    }
  }
}

DebugStop DebugSession::makeStop(DebugRun How) {
  const StopInfo &Info = R->LastStop;
  DebugStop Stop;
  Stop.Robot = R->Selected;
  Stop.Breakpoints = Info.Breakpoints;
  Stop.Description = Info.Why;
  switch (Info.End) {
  case StepEnd::Ran:
    Stop.Why = How == DebugRun::Continue ? DebugStop::Pause : DebugStop::Step;
    Stop.Description = How == DebugRun::Continue
                           ? "ran " + std::to_string(MaxCycles) + " cycles"
                           : "cycle " + std::to_string(getCycle());
    return Stop;
  case StepEnd::Broken: {
    static const char *Ids[] = {"", "assertion", "crash", "timeout",
                                "diverged"};
    Stop.Why = DebugStop::Exception;
    Stop.ExceptionId = Ids[Info.Broke];
    Stop.Description = Info.Broke == StopInfo::Assertion
                           ? (Info.Assumption ? "an assumption does not hold"
                                              : "an assertion failed")
                       : Info.Broke == StopInfo::TimedOut
                           ? "the cycle ran out of time"
                       : Info.Broke == StopInfo::Diverged
                           ? "the re-run differs from the live run"
                           : "the cycle crashed";
    return Stop;
  }
  case StepEnd::Stopped:
    break;
  }
  if (Info.Interrupted) {
    Stop.Why = DebugStop::Pause;
    return Stop;
  }
  if (Info.EntryFailed) {
    Stop.Why = DebugStop::Exception;
    Stop.ExceptionId = "taskFailure";
    return Stop;
  }
  if (Info.Predicate || Info.Breakpoints.empty()) {
    Stop.Why = DebugStop::Step;
    return Stop;
  }
  unsigned First = Info.Breakpoints.front();
  if (llvm::is_contained(FilterNumbers, First)) {
    auto It = llvm::find_if(
        R->Breakpoints, [&](const Breakpoint &B) { return B.Number == First; });
    Stop.Why = DebugStop::Exception;
    Stop.ExceptionId = It != R->Breakpoints.end() && It->K == Breakpoint::Budget
                           ? "budget"
                           : "taskFailure";
    // "breakpoint 1, Faults::spin failed": the filter set it, not the user.
    Stop.Description = llvm::StringRef(Info.Why).split(", ").second.str();
  } else {
    Stop.Why = llvm::is_contained(TaskNumbers, First)
                   ? DebugStop::TaskBreakpoint
                   : DebugStop::Breakpoint;
  }
  return Stop;
}

DebugStop DebugSession::reverseContinue() {
  DebugStop Stop;
  Stop.Robot = R->Selected;
  if (!R->checkHistory(R->addBuffer(":back"))) {
    R->flushDiagnostics();
    Stop.Description = "cycle " + std::to_string(getCycle());
    return Stop;
  }
  uint32_t Now = getCycle(), First = R->History->first();
  // The cycles before now, from the history's start, each checked as a run
  // would check it (hit counts and logpoints left alone); the last that
  // would have stopped is where to go.
  std::optional<uint32_t> Found;
  std::string Why;
  std::vector<unsigned> Hit;
  unsigned HitRobot = 0;
  if (Now > First + 1 && R->travelTo(First)) {
    R->rebaseWatches();
    for (uint32_t Cycle = First + 1; Cycle < Now; ++Cycle) {
      if (!R->travelTo(Cycle))
        break;
      for (unsigned K = 0; K < R->Robots->size(); ++K) {
        R->LastStop.Breakpoints.clear();
        std::string W = R->checkRobotBreakpoints(K, /*Counting=*/false);
        if (W.empty())
          continue;
        Found = Cycle;
        Why = W;
        Hit = R->LastStop.Breakpoints;
        HitRobot = K;
        break;
      }
    }
  }
  R->travelTo(Found ? *Found : First);
  R->flushDiagnostics();
  if (Found) {
    R->selectRobot(HitRobot);
    R->reportStop(Why);
    Stop.Robot = HitRobot;
    Stop.Why = DebugStop::Breakpoint;
    Stop.Description = Why;
    Stop.Breakpoints = Hit;
  } else {
    R->showCycle();
    Stop.Description =
        "the start of the history, cycle " + std::to_string(getCycle());
  }
  return Stop;
}

std::optional<DebugStop> DebugSession::gotoCycle(uint32_t Cycle) {
  R->cmdGoto(std::to_string(Cycle), R->addBuffer(":goto"));
  R->flushDiagnostics();
  if (getCycle() != Cycle)
    return std::nullopt;
  DebugStop Stop;
  Stop.Why = DebugStop::Goto;
  Stop.Robot = R->Selected;
  Stop.Description = "cycle " + std::to_string(Cycle);
  return Stop;
}

//===----------------------------------------------------------------------===//
// Frames and values
//===----------------------------------------------------------------------===//

/// The absolute path of the file `D` is in.
static std::string filePath(const llvm::SourceMgr &SM, const Decl *D) {
  unsigned Buffer = SM.FindBufferContainingLoc(D->getLoc());
  if (!Buffer)
    return "";
  llvm::SmallString<256> Path(
      SM.getMemoryBuffer(Buffer)->getBufferIdentifier());
  llvm::sys::fs::make_absolute(Path);
  llvm::sys::path::remove_dots(Path, /*remove_dot_dot=*/true);
  return Path.str().str();
}

std::vector<DebugFrame> DebugSession::getFrames(unsigned Robot) const {
  const BehaviorSession &S = (*R->Robots)[Robot];
  const LoadedBehavior &L = *R->L;
  std::vector<DebugFrame> Frames;
  debug::ActiveTree Tree;
  if (S.getCycle() > 0)
    Tree = debug::buildActiveTree(
        L.Tables, debug::takeSnapshot(S.getState(), &S.getInfo()));
  if (Tree.Roots.empty()) {
    // Before the first cycle (or an entry that is a func): the entry.
    DebugFrame F;
    F.Name = L.Entry->getQualifiedName() +
             (S.getCycle() ? " [no task ran]" : " [before the first cycle]");
    F.Path = filePath(R->C->SM, L.Entry);
    F.Line = R->C->SM.getLineAndColumn(L.Entry->getLoc()).first;
    Frames.push_back(F);
    return Frames;
  }
  // Every active task, named by its path from the root; a hierarchy has
  // branches, a stack has none: depth first as `:tasks` lists them, then
  // reversed, so that the last branch's innermost task is on top and each
  // task is below those it called.
  std::function<void(unsigned, const std::string &)> Visit =
      [&](unsigned N, const std::string &Parents) {
        const debug::ActiveTask &Node = Tree.Nodes[N];
        const debug::DebugTables::Task &T = L.Tables.Tasks[Node.Record.Task];
        DebugFrame F;
        F.Task = Node.Record.Task;
        std::string Path = Parents + T.ShortName;
        F.Name = Path + " [" +
                 debug::describeActivation(L.Tables, Node.Record) + "]";
        F.Path = filePath(R->C->SM, L.Layout.Tasks[Node.Record.Task].Decl);
        F.Waiting = Node.Record.Resume > 0;
        F.Running = Node.Record.State > 0;
        F.Line = F.Waiting ? T.YieldLines[Node.Record.Resume - 1] : T.Line;
        Frames.push_back(F);
        for (unsigned Child : Node.Children)
          Visit(Child, Path + " > ");
      };
  for (unsigned Root : Tree.Roots)
    Visit(Root, "");
  std::reverse(Frames.begin(), Frames.end());
  return Frames;
}

std::vector<DebugValue> DebugSession::getFields(unsigned Robot,
                                                const DebugFrame &Frame) const {
  std::vector<DebugValue> Fields;
  if (!Frame.Task)
    return Fields;
  const BehaviorSession &S = (*R->Robots)[Robot];
  const BehaviorLayout::Task &T = R->L->Layout.Tasks[*Frame.Task];
  const auto *State = static_cast<const char *>(S.getState());
  const std::string &Task = R->L->Tables.Tasks[*Frame.Task].ShortName;
  for (const BehaviorLayout::FrameField &F : T.Fields) {
    // A finished task's locals are gone (the next call starts afresh).
    if (!llvm::isa<ParamDecl>(F.D) && !Frame.Waiting)
      continue;
    DebugValue V;
    V.Name = F.D->getName().Name.str();
    V.Type = F.Ty->getName().str();
    V.Value = R->Values->read(F.Ty, State + F.Offset);
    V.Display = debug::formatValue(F.Ty, V.Value);
    V.Path = Task + "." + V.Name;
    Fields.push_back(std::move(V));
  }
  return Fields;
}

/// `input` or `output` (`Name`) of class `Class` at `Object`, if there is
/// a class.
static std::optional<DebugValue> readWorldObject(debug::ValueIO &Values,
                                                 const NativeClass *Class,
                                                 const void *Object,
                                                 const char *Name) {
  if (!Class)
    return std::nullopt;
  DebugValue V;
  V.Name = V.Path = Name;
  V.Type = Class->QualifiedName;
  V.Value = Values.readClass(*Class, Object);
  return V;
}

std::optional<DebugValue> DebugSession::getInput(unsigned Robot) const {
  return readWorldObject(*R->Values, R->L->InputClass,
                         (*R->Robots)[Robot].getInput(), "input");
}

std::optional<DebugValue> DebugSession::getOutput(unsigned Robot) const {
  return readWorldObject(*R->Values, R->L->OutputClass,
                         (*R->Robots)[Robot].getOutput(), "output");
}

std::optional<DebugValue> DebugSession::evaluate(llvm::StringRef Line,
                                                 unsigned Robot,
                                                 std::optional<unsigned> Task) {
  R->selectRobot(Robot);
  // In the frame's scope for this line only; `:frame` in the console sets
  // the scope of the lines after it.
  const TaskDecl *Frame = R->Checker->getFrame();
  if (Task)
    R->Checker->setFrame(llvm::cast<TaskDecl>(R->L->Layout.Tasks[*Task].Decl));
  std::optional<LineValue> V = R->runLine(Line);
  R->Checker->setFrame(Frame);
  R->flushDiagnostics();
  if (!V)
    return std::nullopt;
  DebugValue Result;
  Result.Path = Line.str();
  if (V->Ty) {
    Result.Type = V->Ty->getName().str();
    Result.Display = debug::formatValue(V->Ty, V->Value);
    Result.Value = std::move(V->Value);
  }
  return Result;
}

void DebugSession::runConsoleLine(llvm::StringRef Line, unsigned Robot) {
  R->selectRobot(Robot);
  R->handleLine(Line);
  R->flushDiagnostics();
}

std::optional<DebugValue> DebugSession::setInput(llvm::StringRef Path,
                                                 llvm::StringRef Value,
                                                 unsigned Robot) {
  if (!Path.starts_with("input.") && !Path.starts_with("input[")) {
    *ErrorStream << "only members of input can be set here; a line such as '"
                 << Path << " = " << Value
                 << "' in the debug console changes anything else\n";
    return std::nullopt;
  }
  if (!evaluate((Path + " = " + Value).str(), Robot, std::nullopt))
    return std::nullopt;
  return evaluate(Path, Robot, std::nullopt);
}

std::vector<std::string> DebugSession::complete(llvm::StringRef Text,
                                                size_t Pos) const {
  std::vector<std::string> Names;
  for (const llvm::LineEditor::Completion &C : R->complete(Text, Pos))
    Names.push_back(C.DisplayText);
  return Names;
}
