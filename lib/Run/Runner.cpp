//===- Runner.cpp - `bsc run`: cycles, with trace, record and replay ------===//
//
// Runs cycles of a session, or of each robot of a team in index order,
// under its guard. Everything printed about the behavior (traces, outputs,
// recordings) goes through bsc/Debug; a replay (ReplayReader.h) writes
// each line's inputs before the cycle and compares its outputs after it
// (RunnerCheck.cpp).
// A team's lines carry `robot` (docs/repl.md "A team in one process"):
// a recording has one line per robot and cycle, robots in index order.
//
//===----------------------------------------------------------------------===//
#include "RunnerImpl.h"
#include "bsc/Basic/JSON.h"
#include "bsc/Basic/Output.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/ToolOutputFile.h"

using namespace bsc;

/// `--cycle-budget`: a warning at the loop that ran out first (the
/// behavior went on: its task failed), with how many cycles ran out.
static void reportBudgetRanOut(Compilation &C, const LoadedBehavior &L,
                               const BehaviorSession &S, uint32_t Cycle,
                               const bs_loop_info &Loop, unsigned RanOut) {
  const bs_budget_layout &Budget = S.getInfo().budget;
  size_t Index = &Loop - Budget.loops;
  const BehaviorLayout::BudgetLayout::Loop &Where = L.Layout.Budget.Loops[Index];
  C.Diags.report(Where.Loc, llvm::isa<TaskDecl>(Where.Owner)
                                ? diag::warn_budget_ran_out_task
                                : diag::warn_budget_ran_out_func)
      << Cycle << Budget.budget << Where.Owner->getQualifiedName();
  if (RanOut > 1)
    C.Diags.report(Where.Loc, diag::note_budget_ran_out_count) << RanOut;
}

bool CycleRunner::openReplay() {
  if (Opts.CyclesGiven) {
    C.Diags.report(llvm::SMLoc(), diag::err_conflicting_options)
        << "--cycles" << "--replay";
    return false;
  }
  Replay.emplace(C, L);
  if (!Replay->open(Opts.ReplayPath))
    return false;
  unsigned Recorded = Replay->countRobots();
  if (Opts.RobotsFromRecording && T && Recorded > Robots.size()) {
    if (!T->grow(C, L, Recorded))
      return false;
    for (unsigned K = Robots.size(); K < Recorded; ++K)
      Robots.emplace_back(&(*T)[K], Opts.Trace);
  }
  if (Recorded != Robots.size()) {
    C.Diags.report(llvm::SMLoc(), diag::err_replay_robot_count)
        << Opts.ReplayPath << Recorded << unsigned(Robots.size());
    return false;
  }
  // Exact when the recording is of this behavior and has its calls.
  const RecordingHeader &H = Replay->getHeader();
  std::string Why;
  if (H.Format < 2)
    Why = "the recording is of format 1, without its calls into C++";
  else if (Opts.Regression)
    Why = "as '--regression' asks";
  else if (H.Behavior != L.Hash)
    Why = "it was recorded with another version of the behavior, its "
          "bindings or its entry";
  Exact = Why.empty();
  // A robot's object without assertions never made their conditions'
  // calls: the replay makes them for real.
  for (RobotRun &R : Robots)
    R.S->replayMakesAssertionCalls(Exact && !H.Assertions);
  if (Opts.ReplayedExactly)
    *Opts.ReplayedExactly = Exact;
  if (Opts.AnnounceReplayMode) {
    if (Exact)
      C.Diags.report(llvm::SMLoc(), diag::note_replay_exact)
          << Opts.ReplayPath;
    else
      C.Diags.report(llvm::SMLoc(), diag::note_replay_regression)
          << Opts.ReplayPath << Why;
  }
  return true;
}

/// `--record` path `Path` with each `%r` replaced by robot `K`'s number.
static std::string robotPath(llvm::StringRef Path, unsigned K) {
  std::string File;
  for (;;) {
    auto [Before, After] = Path.split("%r");
    File += Before.str();
    if (Before.size() == Path.size()) // No `%r` left.
      return File;
    File += std::to_string(K);
    Path = After;
  }
}

bool CycleRunner::openRecordings() {
  llvm::StringRef Path = Opts.RecordPath;
  bool Binary = isBinaryLogPath(Path);
  if (Binary && !checkWorldAsBytes(C.Diags, llvm::SMLoc(), L, Path))
    return false;
  auto Open = [&](const std::string &File,
                  std::unique_ptr<llvm::ToolOutputFile> &Into,
                  std::unique_ptr<BinaryLogWriter> &Log, unsigned Count) {
    Into = openOutput(C.Diags, File, /*Text=*/!Binary);
    if (!Into)
      return false;
    if (Binary) {
      Log = std::make_unique<BinaryLogWriter>(
          Into->os(), logHeader(C, L, *Robots[0].S, Count),
          /*Compress=*/true);
      return true;
    }
    debug::printJSON(Into->os(), recordHeader(L));
    Into->os() << "\n";
    return true;
  };
  // Each cycle's calls into C++ go into the recording.
  for (RobotRun &R : Robots)
    R.S->keepCalls(true);
  if (!Path.contains("%r"))
    return Open(Path.str(), Record, Log, Robots.size());
  for (unsigned K = 0; K < Robots.size(); ++K)
    if (!Open(robotPath(Path, K), Robots[K].Record, Robots[K].Log, 1))
      return false;
  return true;
}

bool CycleRunner::open() {
  if (!Opts.ReplayPath.empty() && !openReplay())
    return false;
  // Cycles handed over carry the input the entry saw, as recordings do.
  if (Opts.TakeCycle)
    for (RobotRun &R : Robots)
      R.S->keepCalls(true);
  if (!Opts.RecordPath.empty() && !openRecordings())
    return false;
  const TaskDecl *EntryTask = llvm::dyn_cast<TaskDecl>(L.Entry);
  for (unsigned T = 0; T < L.Layout.Tasks.size(); ++T)
    if (L.Layout.Tasks[T].Decl == EntryTask)
      EntryIndex = T;
  if (!Opts.TraceTask.empty()) {
    for (unsigned T = 0; T < L.Tables.Tasks.size(); ++T)
      if (L.Tables.Tasks[T].Name == Opts.TraceTask ||
          L.Tables.Tasks[T].ShortName == Opts.TraceTask)
        TraceSubtree = T;
    if (!TraceSubtree) {
      C.Diags.report(llvm::SMLoc(), diag::err_bad_trace_mode)
          << Opts.TraceTask;
      return false;
    }
  }
  return true;
}

bool CycleRunner::run() {
  bool OK = Replay ? replay() : runCycles();
  keepRecordings();
  if (!OK)
    return false;
  for (unsigned K = 0; K < Robots.size(); ++K)
    if (const RobotRun &R = Robots[K]; R.FirstRanOut) {
      reportBudgetRanOut(C, L, *R.S, R.FirstRanOut->first,
                         *R.FirstRanOut->second, R.RanOut);
      noteRobot(C, K, Robots.size());
    }
  return true;
}

bool CycleRunner::runCycles() {
  for (unsigned I = 0; I < Opts.Cycles; ++I) {
    for (unsigned K = 0; K < Robots.size(); ++K)
      if (!runCycle(K, nullptr))
        return false;
    if (Opts.StopAfterCycle && Opts.StopAfterCycle())
      break;
  }
  return true;
}

bool CycleRunner::replay() {
  ReplayLine Line;
  unsigned Next = 0; // The robot whose line comes next.
  while (Replay->next(Line)) {
    unsigned Robot = Line.Robot.value_or(0);
    if (Robot != Next || (isTeam() && !Line.Robot)) {
      std::string Found = Line.Robot
                              ? "robot " + std::to_string(*Line.Robot) + "'s"
                              : "one without 'robot'";
      C.Diags.report(Line.Loc, diag::err_replay_robot_order)
          << Robots[Next].S->getCycle() + 1 << Next << Found;
      return false;
    }
    if (!runCycle(Next, &Line))
      return false;
    Next = (Next + 1) % Robots.size();
    if (Next == 0 && Opts.StopAfterCycle && Opts.StopAfterCycle())
      return true;
  }
  if (Replay->failed())
    return false;
  if (Next != 0) {
    C.Diags.report(llvm::SMLoc(), diag::err_replay_team_ends)
        << Next - 1 << Robots[Next - 1].S->getCycle() << Next;
    return false;
  }
  return true;
}

bool CycleRunner::writeInput(BehaviorSession &S, const ReplayLine &Line) {
  if (Line.Logged) { // Bytes laid out as here (ReplayReader::openLog).
    // The output too: the robot's software may have changed it since the
    // cycle before (a robot that builds its requests afresh each frame).
    const BinaryLogCycle &Logged = *Line.Logged;
    if (!Logged.Input.empty())
      std::memcpy(S.getInput(), Logged.Input.data(), Logged.Input.size());
    if (!Logged.EntryOutput.empty())
      std::memcpy(S.getOutput(), Logged.EntryOutput.data(),
                  Logged.EntryOutput.size());
    return true;
  }
  // A recording's text is written as it is read; anything else (and any
  // mistake, for its message) goes through a tree. A setter the fast path
  // called before it gave up is then called once more, with the same value.
  if (Values.writeClassText(*L.InputClass, S.getInput(), Line.Input))
    return true;
  std::optional<llvm::json::Value> In = parseJSONLine(C.Diags, Line.Input);
  if (!In)
    return false;
  if (llvm::Error E =
          Values.writeClass(*L.InputClass, S.getInput(), *In, "input")) {
    C.Diags.report(Line.Loc, diag::err_replay_value)
        << llvm::toString(std::move(E));
    return false;
  }
  return true;
}

bool CycleRunner::runCycle(unsigned K, const ReplayLine *Line) {
  BehaviorSession &S = *Robots[K].S;
  uint32_t Cycle = S.getCycle() + 1;
  if (Line && (!Line->Input.empty() || Line->Logged) &&
      !writeInput(S, *Line)) {
    Broken = true;
    return false;
  }
  BehaviorSession::Outcome O;
  if (isTeam())
    startExplainLog(L); // Not the robot before's conditions too.
  if (Line && Exact) {
    CycleRecord Calls;
    if (Line->Logged) {
      Calls.Calls = Line->Logged->Calls;
      Calls.NumCalls = Line->Logged->NumCalls;
    } else if (!Line->Calls.empty()) {
      std::optional<llvm::json::Value> V = parseJSONLine(C.Diags, Line->Calls);
      std::string Error;
      if (!V || !parseRecordedCalls(*V, S, Calls, Error)) {
        if (V)
          C.Diags.report(Line->Loc, diag::err_replay_calls) << Error;
        Broken = true;
        return false;
      }
    }
    O = S.replayCycle(Opts.CycleLimitMs, Calls, /*PrintAgain=*/true);
  } else {
    // A replay's inputs are the recording's: no world hook feeds them.
    O = S.runCycle(Opts.CycleLimitMs, /*WithWorld=*/!Line);
  }
  if (!reportOutcome(C, L, O, Cycle, Opts.CycleLimitMs)) {
    noteRobot(C, K, Robots.size());
    Broken = true;
    return false;
  }
  RobotRun &R = Robots[K];
  if (const bs_loop_info *Loop = bs_budget_ran_out(S.getState(), &S.getInfo())) {
    ++R.RanOut;
    if (!R.FirstRanOut)
      R.FirstRanOut = {Cycle, Loop};
  }

  // The objects are read as JSON only for what asks for them: a plain
  // run of many cycles does no more than the robot would.
  RobotRun &Run = Robots[K];
  bool Text = recording() && !Log && !Run.Log;
  llvm::json::Value Rec = Text ? recordCycle(Values, L, S) : nullptr;
  if (Log)
    logCycle(*Log, K, L, S);
  else if (Run.Log)
    logCycle(*Run.Log, 0, L, S);
  llvm::json::Value Out = nullptr;
  if (Text && L.OutputClass)
    Out = *Rec.getAsObject()->get("output");
  else if (L.OutputClass && Opts.PrintOutput)
    Out = Values.readClass(*L.OutputClass, S.getOutput());
  if (Opts.TakeCycle && !Opts.TakeCycle(K, S)) {
    Broken = true;
    return false;
  }
  writeCycle(K, std::move(Rec), Out);
  if (Opts.Explain && Line)
    return explainFailure(K, S, *Line, Cycle);
  checkEntryFailed(K, Cycle);
  if (Line && (!Line->Output.empty() || Line->Logged) &&
      !checkOutput(S, *Line, Cycle)) {
    noteRobot(C, K, Robots.size());
    return false;
  }
  // The robot's tables are this behavior's only in an exact replay.
  if (Line && Line->Logged && Exact && !Line->Logged->Trace.empty() &&
      !checkLoggedTasks(S, *Line->Logged, Cycle)) {
    noteRobot(C, K, Robots.size());
    return false;
  }
  return true;
}

void CycleRunner::writeCycle(unsigned K, llvm::json::Value Rec,
                             const llvm::json::Value &Out) {
  RobotRun &R = Robots[K];
  int64_t Cycle = R.S->getCycle();
  // A team's lines name the robot: `cycle 3, robot 1: ...`, "robot":1.
  std::string Robot = isTeam() ? ", robot " + std::to_string(K) : "";
  if (Opts.Trace != debug::TraceMode::Off) {
    std::string Trace = debug::formatTraceLine(
        L.Tables, debug::takeSnapshot(R.S->getState(), &R.S->getInfo()),
        TraceSubtree);
    if (R.Traces.shouldPrint(Trace))
      OS << "cycle " << Cycle << Robot << ": " << Trace << "\n";
  }
  if (Opts.PrintOutput && L.OutputClass) {
    llvm::json::Object Line{{"cycle", Cycle}, {"output", Out}};
    if (isTeam())
      Line["robot"] = int64_t(K);
    debug::printJSON(OS, std::move(Line));
    OS << "\n";
  }
  OS.flush();
  if (R.Log || Log) {
    // Written by runCycle.
  } else if (R.Record) {
    debug::printJSON(R.Record->os(), Rec);
    R.Record->os() << "\n";
  } else if (Record) {
    if (isTeam())
      (*Rec.getAsObject())["robot"] = int64_t(K);
    debug::printJSON(Record->os(), Rec);
    Record->os() << "\n";
  }
}

void CycleRunner::checkEntryFailed(unsigned K, uint32_t Cycle) {
  RobotRun &R = Robots[K];
  if (!EntryIndex || R.ReportedFailure)
    return;
  int32_t State =
      bs_task_state_at(R.S->getState(), &R.S->getInfo().tasks[*EntryIndex]);
  if (State < 0) {
    C.Diags.report(L.Entry->getLoc(), diag::warn_entry_failed)
        << L.Entry->getQualifiedName() << State << Cycle;
    noteRobot(C, K, Robots.size());
    R.ReportedFailure = true;
  }
}

void CycleRunner::keepRecordings() {
  if (Broken)
    return;
  if (Log)
    Log->finish();
  for (RobotRun &R : Robots)
    if (R.Log)
      R.Log->finish();
  if (Record)
    Record->keep();
  for (RobotRun &R : Robots)
    if (R.Record)
      R.Record->keep();
}

bool bsc::runBehavior(Compilation &C, LoadedBehavior &L, BehaviorSession &S,
                      const RunOptions &Opts, llvm::raw_ostream &OS) {
  BehaviorSession *One = &S;
  CycleRunner Runner(C, L, nullptr, One, Opts, OS);
  return Runner.open() && Runner.run();
}

bool bsc::runTeam(Compilation &C, LoadedBehavior &L, Team &T,
                  const RunOptions &Opts, llvm::raw_ostream &OS) {
  CycleRunner Runner(C, L, &T, T.getSessions(), Opts, OS);
  return Runner.open() && Runner.run();
}
