//===- Runner.cpp - `bsc run`: cycles, with trace, record and replay ------===//
//
// Runs cycles of a session under its guard. Everything printed about the
// behavior (traces, outputs, recordings) goes through bsc/Debug; a replay
// (ReplayReader.h) writes each line's inputs before the cycle and
// compares its outputs after it.
//
//===----------------------------------------------------------------------===//
#include "ReplayReader.h"
#include "bsc/Basic/JSON.h"
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

/// A replayed cycle whose output differs from the line's: one error, then
/// a note per field that differs, at the line. Neither echoes it: a
/// recording fills it with every output member. Returns whether it
/// reported.
static bool reportMismatch(Compilation &C, const ReplayLine &Line,
                           uint32_t Cycle, const llvm::json::Value &Recorded,
                           const llvm::json::Value &Got) {
  std::vector<debug::Difference> Ds =
      debug::findDifferences(Recorded, Got, "output");
  if (Ds.empty())
    return false;
  C.Diags.report(Line.Loc, diag::err_replay_mismatch) << Cycle << NoSourceLine();
  for (const debug::Difference &D : Ds)
    C.Diags.report(Line.Loc, diag::note_replay_difference)
        << D.Path << D.Recorded << D.Got << NoSourceLine();
  return true;
}

namespace {
/// One `bsc run`: its replay lines and recording file, and what it has
/// seen so far (the first cycle a budget ran out in, the entry's failure).
class CycleRunner {
public:
  CycleRunner(Compilation &C, LoadedBehavior &L, BehaviorSession &S,
              const RunOptions &Opts, llvm::raw_ostream &OS)
      : C(C), L(L), S(S), Opts(Opts), OS(OS), Traces(Opts.Trace),
        Values([&L](llvm::StringRef Sym) { return L.JIT->lookup(Sym); }) {}

  /// Opens the replay file and the recording. False after reporting.
  bool open();
  /// Runs the cycles the options ask for. False after reporting.
  bool run();

private:
  /// Runs one cycle, fed by `Line` if replaying. False after reporting.
  bool runCycle(const ReplayLine *Line);
  /// The line's input into the input object. False after reporting.
  bool writeInput(const ReplayLine &Line);
  /// Whether the output object holds the line's output; if not, reports
  /// the differences.
  bool checkOutput(const ReplayLine &Line, uint32_t Cycle);
  /// The trace line, the output line and the recording of the cycle just
  /// run, each only if asked for.
  void writeCycle(const llvm::json::Value &Rec, const llvm::json::Value &Out);
  /// Warns once, at the first cycle the entry task ends in failure.
  void checkEntryFailed(uint32_t Cycle);
  /// `--record`: keeps the file (even after a mismatch, to compare).
  void keepRecording() {
    if (Record)
      Record->keep();
  }

  Compilation &C;
  LoadedBehavior &L;
  BehaviorSession &S;
  const RunOptions &Opts;
  llvm::raw_ostream &OS;
  debug::TraceFilter Traces;
  debug::ValueIO Values;
  std::optional<ReplayReader> Replay;
  std::unique_ptr<llvm::ToolOutputFile> Record;
  /// The entry task's place in the task table, whose state tells a failure.
  std::optional<unsigned> EntryIndex;
  bool ReportedFailure = false;
  /// `--cycle-budget`: the first cycle that ran out, and how many did.
  std::optional<std::pair<uint32_t, const bs_loop_info *>> FirstRanOut;
  unsigned RanOut = 0;
};
} // namespace

bool CycleRunner::open() {
  if (!Opts.ReplayPath.empty()) {
    if (Opts.CyclesGiven) {
      C.Diags.report(llvm::SMLoc(), diag::err_conflicting_options)
          << "--cycles" << "--replay";
      return false;
    }
    Replay.emplace(C, L);
    if (!Replay->open(Opts.ReplayPath))
      return false;
  }
  if (!Opts.RecordPath.empty()) {
    std::error_code EC;
    Record = std::make_unique<llvm::ToolOutputFile>(Opts.RecordPath, EC,
                                                    llvm::sys::fs::OF_Text);
    if (EC) {
      C.Diags.report(llvm::SMLoc(), diag::err_cannot_write_output)
          << Opts.RecordPath << EC.message();
      return false;
    }
  }
  const TaskDecl *EntryTask = llvm::dyn_cast<TaskDecl>(L.Entry);
  for (unsigned T = 0; T < L.Layout.Tasks.size(); ++T)
    if (L.Layout.Tasks[T].Decl == EntryTask)
      EntryIndex = T;
  return true;
}

bool CycleRunner::run() {
  ReplayLine Line;
  for (unsigned I = 0; Replay ? Replay->next(Line) : I < Opts.Cycles; ++I) {
    if (!runCycle(Replay ? &Line : nullptr))
      return false;
    if (Opts.StopAfterCycle && Opts.StopAfterCycle())
      break;
  }
  if (Replay && Replay->failed()) {
    keepRecording();
    return false;
  }
  if (FirstRanOut)
    reportBudgetRanOut(C, L, S, FirstRanOut->first, *FirstRanOut->second,
                       RanOut);
  keepRecording();
  return true;
}

bool CycleRunner::writeInput(const ReplayLine &Line) {
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

bool CycleRunner::checkOutput(const ReplayLine &Line, uint32_t Cycle) {
  // Compared member by member along the text; only a difference (or text
  // of another form) builds trees, which name the differences.
  if (Values.matchesClassText(*L.OutputClass, S.getOutput(), Line.Output))
    return true;
  std::optional<llvm::json::Value> Recorded =
      parseJSONLine(C.Diags, Line.Output);
  return Recorded &&
         !reportMismatch(C, Line, Cycle, *Recorded,
                         Values.readClass(*L.OutputClass, S.getOutput()));
}

bool CycleRunner::runCycle(const ReplayLine *Line) {
  uint32_t Cycle = S.getCycle() + 1;
  if (Line && !Line->Input.empty() && !writeInput(*Line))
    return false;
  BehaviorSession::Outcome O = S.runCycle(Opts.CycleLimitMs);
  if (!reportOutcome(C, L, O, Cycle, Opts.CycleLimitMs))
    return false;
  if (const bs_loop_info *Loop = bs_budget_ran_out(S.getState(), &S.getInfo())) {
    ++RanOut;
    if (!FirstRanOut)
      FirstRanOut = {Cycle, Loop};
  }

  // The objects are read as JSON only for what asks for them: a plain
  // run of many cycles does no more than the robot would.
  llvm::json::Value Rec = Record ? recordCycle(Values, L, S) : nullptr;
  llvm::json::Value Out = nullptr;
  if (Record && L.OutputClass)
    Out = *Rec.getAsObject()->get("output");
  else if (L.OutputClass && Opts.PrintOutput)
    Out = Values.readClass(*L.OutputClass, S.getOutput());
  writeCycle(Rec, Out);
  checkEntryFailed(Cycle);
  if (Line && !Line->Output.empty() && !checkOutput(*Line, Cycle)) {
    keepRecording();
    return false;
  }
  return true;
}

void CycleRunner::writeCycle(const llvm::json::Value &Rec,
                             const llvm::json::Value &Out) {
  int64_t Cycle = S.getCycle();
  if (Opts.Trace != debug::TraceMode::Off) {
    std::string Trace = debug::formatTraceLine(
        L.Tables, debug::takeSnapshot(S.getState(), &S.getInfo()));
    if (Traces.shouldPrint(Trace))
      OS << "cycle " << Cycle << ": " << Trace << "\n";
  }
  if (Opts.PrintOutput && L.OutputClass) {
    debug::printJSON(OS, llvm::json::Object{{"cycle", Cycle}, {"output", Out}});
    OS << "\n";
  }
  OS.flush();
  if (Record) {
    debug::printJSON(Record->os(), Rec);
    Record->os() << "\n";
  }
}

void CycleRunner::checkEntryFailed(uint32_t Cycle) {
  if (!EntryIndex || ReportedFailure)
    return;
  int32_t State =
      bs_task_state_at(S.getState(), &S.getInfo().tasks[*EntryIndex]);
  if (State < 0) {
    C.Diags.report(L.Entry->getLoc(), diag::warn_entry_failed)
        << L.Entry->getQualifiedName() << State << Cycle;
    ReportedFailure = true;
  }
}

bool bsc::runBehavior(Compilation &C, LoadedBehavior &L, BehaviorSession &S,
                      const RunOptions &Opts, llvm::raw_ostream &OS) {
  CycleRunner Runner(C, L, S, Opts, OS);
  return Runner.open() && Runner.run();
}
