//===- RunnerCheck.cpp - a replayed cycle against its recorded line --------===//
//
// After a replayed cycle, what it left is compared with what the line
// recorded: the output (--ignore and --tolerance say which differences
// count), and with a robot's trace record the tasks. A failing log's second
// replay (RunOptions::Explain) looks at each cycle for the first task that
// parted from the recording and explains it.
//
//===----------------------------------------------------------------------===//
#include "RunnerImpl.h"
#include "bsc/Basic/JSON.h"
#include <cmath>

using namespace bsc;

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
