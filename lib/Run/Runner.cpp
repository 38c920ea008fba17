//===- Runner.cpp - `bsc run`: cycles, with trace, record and replay ------===//
//
// Runs cycles of a session, or of each robot of a team in index order,
// under its guard. Everything printed about the behavior (traces, outputs,
// recordings) goes through bsc/Debug; a replay (ReplayReader.h) writes
// each line's inputs before the cycle and compares its outputs after it.
// A team's lines carry `robot` (docs/repl.md "A team in one process"):
// a recording has one line per robot and cycle, robots in index order.
//
//===----------------------------------------------------------------------===//
#include "FailureCause.h"
#include "ReplayReader.h"
#include "bsc/Basic/JSON.h"
#include "bsc/Basic/Output.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/ToolOutputFile.h"
#include <cmath>

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

/// The differences of `Got` from `Recorded` that count (--ignore,
/// --tolerance).
static std::vector<debug::Difference>
countedDifferences(const llvm::json::Value &Recorded,
                   const llvm::json::Value &Got,
                   const OutputComparison &Compare) {
  std::vector<debug::Difference> Ds;
  for (debug::Difference &D : debug::findDifferences(Recorded, Got, "output"))
    if (Compare.counts(D))
      Ds.push_back(std::move(D));
  return Ds;
}

/// Each difference as a failure's note says it.
static std::vector<std::string>
describeDifferences(llvm::ArrayRef<debug::Difference> Ds) {
  std::vector<std::string> Text;
  for (const debug::Difference &D : Ds)
    Text.push_back(D.Path + ": recorded " + D.Recorded + ", got " + D.Got);
  return Text;
}

/// A replayed cycle whose output differs from the line's: one error, then
/// a note per field that differs, at the line. Neither echoes it: a
/// recording fills it with every output member. Returns whether it
/// reported (and then sets `Failed`, if given).
static bool reportMismatch(Compilation &C, const ReplayLine &Line,
                           uint32_t Cycle, const llvm::json::Value &Recorded,
                           const llvm::json::Value &Got,
                           const OutputComparison &Compare,
                           ReplayFailure *Failed) {
  std::vector<debug::Difference> Ds =
      countedDifferences(Recorded, Got, Compare);
  if (Ds.empty())
    return false;
  C.Diags.report(Line.Loc, diag::err_replay_mismatch) << Cycle << NoSourceLine();
  for (const debug::Difference &D : Ds)
    C.Diags.report(Line.Loc, diag::note_replay_difference)
        << D.Path << D.Recorded << D.Got << NoSourceLine();
  if (Failed)
    *Failed = {Cycle, describeDifferences(Ds)};
  return true;
}

namespace {
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
} // namespace

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

bool CycleRunner::checkOutput(BehaviorSession &S, const ReplayLine &Line,
                              uint32_t Cycle) {
  if (Line.Logged)
    return checkLoggedOutput(S, *Line.Logged, Cycle);
  // Compared member by member along the text; only a difference (or text
  // of another form) builds trees, which name the differences.
  if (Values.matchesClassText(*L.OutputClass, S.getOutput(), Line.Output))
    return true;
  // (With --ignore or --tolerance a difference may not count.)
  std::optional<llvm::json::Value> Recorded =
      parseJSONLine(C.Diags, Line.Output);
  if (Recorded && Opts.Changed) { // --update: counted, not reported.
    for (const debug::Difference &D : countedDifferences(
             *Recorded, Values.readClass(*L.OutputClass, S.getOutput()),
             Opts.Compare))
      ++(*Opts.Changed)[D.Path];
    return true;
  }
  return Recorded &&
         !reportMismatch(C, Line, Cycle, *Recorded,
                         Values.readClass(*L.OutputClass, S.getOutput()),
                         Opts.Compare, Opts.Failed);
}

bool CycleRunner::checkLoggedOutput(BehaviorSession &S,
                                    const BinaryLogCycle &Logged,
                                    uint32_t Cycle) {
  llvm::ArrayRef<unsigned char> Out = Logged.Output;
  if (Out.empty() ||
      std::memcmp(S.getOutput(), Out.data(), Out.size()) == 0)
    return true;
  // Padding or a float's -0 may differ where the members do not: compare
  // the members, as a JSON recording's are.
  std::vector<unsigned char> Copy(Out.begin(), Out.end());
  llvm::json::Value Recorded = Values.readClass(*L.OutputClass, Copy.data());
  llvm::json::Value Got = Values.readClass(*L.OutputClass, S.getOutput());
  if (Opts.Changed) { // --update: counted, not reported.
    for (const debug::Difference &D :
         countedDifferences(Recorded, Got, Opts.Compare))
      ++(*Opts.Changed)[D.Path];
    return true;
  }
  ReplayLine Line;
  return !reportMismatch(C, Line, Cycle, Recorded, Got, Opts.Compare,
                         Opts.Failed);
}

bool CycleRunner::checkLoggedTasks(BehaviorSession &S,
                                   const BinaryLogCycle &Logged,
                                   uint32_t Cycle) {
  llvm::Expected<std::vector<debug::Activation>> Robot =
      debug::decodeTraceRecord(L.Tables, Logged.Trace);
  std::string Want = Robot ? debug::formatTraceLine(L.Tables, *Robot)
                           : "a record that does not fit the behavior: " +
                                 llvm::toString(Robot.takeError());
  std::string Got = debug::formatTraceLine(
      L.Tables, debug::takeSnapshot(S.getState(), &S.getInfo()));
  if (Want == Got)
    return true;
  C.Diags.report(llvm::SMLoc(), diag::err_replay_tasks_differ) << Cycle;
  C.Diags.report(llvm::SMLoc(), diag::note_replay_tasks) << "robot" << Want;
  C.Diags.report(llvm::SMLoc(), diag::note_replay_tasks) << "replay" << Got;
  return false;
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
  if (Opts.Explain && isTeam())
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

std::vector<std::string> CycleRunner::outputDifferences(BehaviorSession &S,
                                                       const ReplayLine &Line) {
  if (!L.OutputClass)
    return {};
  llvm::json::Value Recorded = nullptr;
  if (Line.Logged) {
    llvm::ArrayRef<unsigned char> Out = Line.Logged->Output;
    if (Out.empty() || std::memcmp(S.getOutput(), Out.data(), Out.size()) == 0)
      return {};
    std::vector<unsigned char> Copy(Out.begin(), Out.end());
    Recorded = Values.readClass(*L.OutputClass, Copy.data());
  } else {
    if (Line.Output.empty() ||
        Values.matchesClassText(*L.OutputClass, S.getOutput(), Line.Output))
      return {};
    llvm::Expected<llvm::json::Value> Parsed = llvm::json::parse(Line.Output);
    if (!Parsed) { // The first replay said so.
      llvm::consumeError(Parsed.takeError());
      return {"the recorded output cannot be read"};
    }
    Recorded = std::move(*Parsed);
  }
  return describeDifferences(countedDifferences(
      Recorded, Values.readClass(*L.OutputClass, S.getOutput()), Opts.Compare));
}

bool CycleRunner::explainFailure(unsigned K, BehaviorSession &S,
                                 const ReplayLine &Line, uint32_t Cycle) {
  auto &First = FirstTaskDifference;
  std::optional<std::vector<ActiveTaskView>> Recorded =
      recordedTasks(L, Line);
  if (!First.Cycle && Recorded)
    if (std::optional<TaskDifference> D =
            findTaskDifference(*Recorded, replayedTasks(L, S))) {
      First.Cycle = Cycle;
      if (isTeam())
        First.Robot = K;
      First.Difference = *D;
      // The conditions are of this cycle only: kept now, shown if the
      // replay fails where the first did.
      for (unsigned T = 0; T < L.Tables.Tasks.size(); ++T)
        if (L.Tables.Tasks[T].Name == D->Explains) {
          llvm::raw_string_ostream Why(First.Why);
          if (explainLastCycle(L, Values, S, int(T), Why) !=
              WhyOutcome::Printed)
            First.Why.clear();
        }
    }
  // (A team's other robots may run the failing cycle as recorded.)
  std::vector<std::string> Differences = outputDifferences(S, Line);
  uint32_t FailedAt = Opts.Explain->Cycle;
  if (Differences.empty() && Cycle <= FailedAt)
    return true;
  if (Cycle != FailedAt || Differences != Opts.Explain->Differences) {
    C.Diags.report(Line.Loc, diag::note_replay_not_explained)
        << (Differences.empty()
                ? "did not fail at cycle " + std::to_string(FailedAt)
            : Cycle != FailedAt
                ? "failed at cycle " + std::to_string(Cycle)
                : "failed otherwise at cycle " + std::to_string(Cycle) +
                      " (" + Differences.front() + ")")
        << NoSourceLine();
    return false;
  }
  if (!First.Cycle) {
    // Without the recording's tasks there is nothing to compare them with:
    // the replay's are what can be said.
    if (Recorded)
      C.Diags.report(Line.Loc, diag::note_replay_tasks_as_recorded)
          << Cycle << NoSourceLine();
    else
      C.Diags.report(Line.Loc, diag::note_replay_no_tasks)
          << Cycle
          << debug::formatTraceLine(
                 L.Tables, debug::takeSnapshot(S.getState(), &S.getInfo()))
          << NoSourceLine();
    return false;
  }
  C.Diags.report(Line.Loc, diag::note_replay_first_task)
      << First.Cycle << First.Difference.Task << First.Difference.Recorded
      << First.Difference.Replayed << NoSourceLine();
  if (First.Robot)
    noteRobot(C, *First.Robot, Robots.size());
  if (!First.Why.empty())
    C.Diags.report(Line.Loc, diag::note_replay_why)
        << First.Difference.Explains << First.Cycle
        << ("\n" + llvm::StringRef(First.Why).rtrim()).str() << NoSourceLine();
  return false;
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

/// Whether `Path` is `Member` or lies under it (`output.a` is under
/// `output`, not under `output.ab`). A member may leave out `output.`.
static bool isUnder(llvm::StringRef Path, llvm::StringRef Member) {
  std::string Full = Member.starts_with("output") ? Member.str()
                                                  : "output." + Member.str();
  if (!Path.starts_with(Full))
    return false;
  llvm::StringRef Rest = Path.drop_front(Full.size());
  return Rest.empty() || Rest.front() == '.' || Rest.front() == '[';
}

bool OutputComparison::counts(const debug::Difference &D) const {
  for (const std::string &Member : Ignore)
    if (isUnder(D.Path, Member))
      return false;
  double Recorded, Got;
  if (llvm::StringRef(D.Recorded).getAsDouble(Recorded) ||
      llvm::StringRef(D.Got).getAsDouble(Got))
    return true; // Not two numbers.
  for (const auto &[Member, Abs] : Tolerance)
    if (isUnder(D.Path, Member) && std::fabs(Recorded - Got) <= Abs)
      return false;
  return true;
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
