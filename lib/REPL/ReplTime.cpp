//===- ReplTime.cpp - time travel: :goto, :back, :history ------------------===//
//
// The REPL keeps a CycleHistory of the session: the input every cycle's
// entry saw (fed by the world, a replay or typed at the prompt), what its
// calls into registered C++ did (bsc/JIT/Boundary.h), and a copy of the
// state every SnapshotEvery cycles. Going to a cycle restores the copy
// before it and re-runs the cycles after the copy on their logged inputs,
// taking every call into C++ (and the world's end hook) from the log: the
// C++ is not called again, prints nothing again, and a random number or
// a clock reads as it did. Each re-run cycle is checked against how the
// live one left the state, input and output; where they part, the history
// ends at the cycle before and the REPL says which value differed.
//
// Stepping from a cycle in the past re-runs the history up to the present,
// then goes on live. A line at the prompt that changes the state, input or
// output in the past ends the history there (the cycles after it are
// forgotten): what follows is another run.
//
// A team (`--robots N`) has a history per robot: given what its history
// logs (its input, its calls, the world's end hook), a robot's cycle
// depends on nothing of the others, so each goes back through its own and
// the team then runs live from where the histories end. Whatever ends one
// robot's history in the past (a re-run that differs, a line at the
// prompt) ends every robot's there: the world they share runs what follows
// anew.
//
// The copies are of bytes, put back where they were taken: a task local,
// `input` or `output` of a registered class whose destructor frees memory
// (a std::vector inside) turns the history off, and the commands say why.
//
//===----------------------------------------------------------------------===//
#include "ReplImpl.h"
#include "llvm/ADT/ScopeExit.h"
#include <algorithm>
#include <cstring>

using namespace bsc;
using namespace bsc::repl;

/// Copies of the state every this many cycles: going to any cycle re-runs
/// at most as many (bench/README.md, "Time travel").
static constexpr unsigned SnapshotEvery = 64;

/// The most changes `:history` prints.
static constexpr unsigned MaxHistoryLines = 200;

/// Why a value of type `T` (`What`) cannot be kept as bytes, or empty. A
/// copy is put back where it was taken, so only a class that frees
/// something when destroyed (a std::vector inside) cannot: the copy would
/// point at memory the live value has freed since. Eigen's vectors and
/// plain structs are fine, whether C++ calls them trivially copyable or not,
/// and so is a class registered `.copyAsBytes()`.
static std::string whyNotBytes(const NativeClass *NC, const std::string &What) {
  if (!NC || NC->TriviallyDestructible || NC->CopiesAsBytes)
    return "";
  return What + " is a '" + NC->QualifiedName +
         "', which has a C++ destructor (a copy of its bytes could point at "
         "what the live value has freed since)";
}

void Repl::startHistory() {
  Histories.clear();
  History = nullptr;
  NoHistory.clear();
  ExplainLogs.assign(Robots->size() > 1 ? Robots->size() : 0, {});
  for (const BehaviorLayout::Task &T : L->Layout.Tasks)
    for (const BehaviorLayout::FrameField &F : T.Fields)
      if (NoHistory.empty())
        NoHistory = whyNotBytes(F.Ty->getClass(),
                                "'" + F.D->getName().Name.str() +
                                    "' of task '" +
                                    T.Decl->getQualifiedName() + "'");
  if (NoHistory.empty())
    NoHistory = whyNotBytes(L->InputClass, "'input'");
  if (NoHistory.empty())
    NoHistory = whyNotBytes(L->OutputClass, "'output'");
  if (!NoHistory.empty())
    return;
  for (unsigned K = 0; K < Robots->size(); ++K) {
    BehaviorSession &R = (*Robots)[K];
    Histories.push_back(std::make_unique<CycleHistory>(
        CycleHistory::Sizes{R.getInfo().state_size, L->Input.Size,
                            L->Output.Size},
        SnapshotEvery));
    Histories.back()->reset(R.getCycle(), getBlocks(R));
    R.keepCalls(true);
  }
  History = Histories[Selected].get();
}

CycleHistory::Blocks Repl::getBlocks(const BehaviorSession &R) {
  return {R.getState(), R.getInput(), R.getOutput()};
}

BehaviorSession::Outcome Repl::runNextCycle(bool &FromHistory,
                                            unsigned &Broke) {
  BehaviorSession::Outcome O;
  for (Broke = 0; Broke < Robots->size(); ++Broke) {
    O = runRobotCycle(Broke, FromHistory);
    if (O.K != BehaviorSession::Outcome::Completed)
      break;
  }
  return O;
}

BehaviorSession::Outcome Repl::runRobotCycle(unsigned K, bool &FromHistory) {
  // Line breakpoints: which statements robot K's cycle ran (the robots
  // share the JIT's counters, and run one after another).
  markCounters();
  auto NoteLines = llvm::make_scope_exit([&] { noteLinesRan(K); });
  BehaviorSession &R = (*Robots)[K];
  CycleHistory *H = Histories.empty() ? nullptr : Histories[K].get();
  uint32_t Next = R.getCycle() + 1;
  FromHistory = H && Next <= H->last();
  BehaviorSession::Outcome O;
  if (!ExplainLogs.empty())
    startExplainLog(*L); // Not the robot before's conditions too.
  if (!FromHistory) {
    O = R.runCycle(Opts.CycleLimitMs);
    if (H) {
      H->recordCycle(R.getLastCalls(), getBlocks(R));
      // A cycle that broke: its moment is the copy (below), and what broke
      // it is kept to say again.
      if (O.K != BehaviorSession::Outcome::Completed) {
        H->keepPresent(Next, getBlocks(R), /*Broken=*/true);
        BrokenOutcomes.insert_or_assign({K, Next}, O);
      }
    }
  } else if (H->isEdited(Next)) {
    // A cycle that broke breaks again on its logged input and calls, and
    // says so as it did live (a failed assertion with its values); then,
    // as after the prompt changed a moment, the copy is that moment.
    if (H->isBroken(Next)) {
      H->applyInput(Next, R.getInput());
      CycleRecord Calls;
      H->getCalls(Next, Calls);
      O = R.replayCycle(Opts.CycleLimitMs, Calls);
      // A crash inside C++ cannot happen again without calling it (its
      // record ends there): the live outcome is what the cycle did.
      auto Live = BrokenOutcomes.find({K, Next});
      if (Live != BrokenOutcomes.end() && O.K != Live->second.K)
        O = Live->second;
    }
    restoreFromHistory(K, Next, /*Before=*/false);
    keepExplainLog(K);
    return O;
  } else {
    H->applyInput(Next, R.getInput());
    CycleRecord Calls;
    H->getCalls(Next, Calls);
    O = R.replayCycle(Opts.CycleLimitMs, Calls);
    if (O.K == BehaviorSession::Outcome::Completed) {
      std::string Why =
          describeViewDifference(*Values, *L, R, H->liveViewAt(Next));
      if (!Why.empty()) {
        O.K = BehaviorSession::Outcome::Diverged;
        O.Divergence = "the re-run differs from the live run: " + Why;
      }
    }
    // Back to the last moment all agree on; what follows is forgotten,
    // for every robot: the world they share runs it anew.
    if (O.K == BehaviorSession::Outcome::Diverged)
      for (unsigned J = 0; J < Robots->size(); ++J)
        endHistoryAt(J, Next - 1);
  }
  keepExplainLog(K);
  return O;
}

void Repl::markCounters() {
  if (tracksLines())
    CountersBefore = readCoverage(*L);
}

void Repl::noteLinesRan(unsigned K) {
  if (!tracksLines())
    return;
  RanCounters.resize(Robots->size());
  RanCycle.resize(Robots->size());
  RanCounters[K].clear();
  RanCycle[K] = (*Robots)[K].getCycle();
  std::vector<uint64_t> After = readCoverage(*L);
  for (unsigned I = 0; I < After.size() && I < CountersBefore.size(); ++I)
    if (After[I] != CountersBefore[I])
      RanCounters[K].push_back(I);
  CountersBefore = std::move(After);
}

void Repl::endHistoryAt(unsigned K, uint32_t Cycle) {
  CycleHistory &H = *Histories[K];
  if (Cycle < H.first() || Cycle > H.last())
    return;
  const std::vector<unsigned char> &View = H.liveViewAt(Cycle);
  CycleHistory::Blocks B = getBlocks((*Robots)[K]);
  size_t Sizes[3];
  (*Robots)[K].getViewSizes(Sizes);
  void *User = bs_state_user(B.State);
  std::memcpy(B.State, View.data(), Sizes[0]);
  bs_state_set_user(B.State, User);
  if (Sizes[1])
    std::memcpy(B.Input, View.data() + Sizes[0], Sizes[1]);
  if (Sizes[2])
    std::memcpy(B.Output, View.data() + Sizes[0] + Sizes[1], Sizes[2]);
  H.keepPresent(Cycle, B);
  if (!ExplainLogs.empty())
    ExplainLogs[K].clear();
}

uint32_t Repl::restoreFromHistory(unsigned K, uint32_t Cycle, bool Before) {
  // The user pointer is the session's (its world set it, perhaps after the
  // copy was taken), not the moment's.
  BehaviorSession &R = (*Robots)[K];
  void *User = bs_state_user(R.getState());
  uint32_t At = Histories[K]->restore(Cycle, Before, getBlocks(R));
  bs_state_set_user(R.getState(), User);
  if (!ExplainLogs.empty()) // Of a cycle that ran before the copy.
    ExplainLogs[K].clear();
  return At;
}

void Repl::recordLiveCycle() {
  for (unsigned K = 0; K < Histories.size(); ++K) {
    BehaviorSession &R = (*Robots)[K];
    Histories[K]->recordCycle(R.getLastCalls(), getBlocks(R));
  }
}

void Repl::forgetFuture() {
  for (unsigned K = 0; K < Histories.size(); ++K) {
    BehaviorSession &R = (*Robots)[K];
    if (R.getCycle() < Histories[K]->last())
      Histories[K]->keepPresent(R.getCycle(), getBlocks(R));
  }
}

void Repl::keepExplainLog(unsigned K) {
  if (ExplainLogs.empty())
    return;
  const ExplainLogHeader *Log = L->ExplainLog;
  std::vector<unsigned char> &Copy = ExplainLogs[K];
  if (!Log) {
    Copy.clear();
    return;
  }
  // The header and the records written, not the whole capacity.
  size_t Size = sizeof(ExplainLogHeader) +
                std::min(Log->Used, ExplainLogCapacity);
  const auto *Bytes = reinterpret_cast<const unsigned char *>(Log);
  Copy.assign(Bytes, Bytes + Size);
}

std::vector<unsigned char> Repl::copyBlocks() const {
  std::vector<unsigned char> Bytes;
  if (!History)
    return Bytes;
  auto Add = [&](const void *P, size_t N) {
    auto *B = static_cast<const unsigned char *>(P);
    if (N) // No `input` or `output`: null.
      Bytes.insert(Bytes.end(), B, B + N);
  };
  Add(S->getState(), S->getInfo().state_size);
  Add(S->getInput(), L->Input.Size);
  Add(S->getOutput(), L->Output.Size);
  return Bytes;
}

void Repl::noteEdits(const std::vector<unsigned char> &Before) {
  if (History && copyBlocks() != Before) {
    History->keepPresent(S->getCycle(), getBlocks(*S));
    forgetFuture();
  }
}

bool Repl::checkHistory(llvm::SMLoc Loc) {
  if (History)
    return true;
  C->Diags.report(Loc, diag::err_repl_no_history) << NoHistory;
  return false;
}

bool Repl::travelTo(uint32_t Target) {
  auto Stopped = [&](const BehaviorSession::Outcome &O, uint32_t Cycle,
                     unsigned Robot) {
    if (reportOutcome(*C, *L, O, Cycle, Opts.CycleLimitMs))
      return false;
    noteRobot(*C, Robot, Robots->size());
    bool Diverged = O.K == BehaviorSession::Outcome::Diverged;
    if (Diverged)
      C->Diags.report(llvm::SMLoc(), diag::note_history_ends) << Cycle - 1;
    flushDiagnostics();
    OS << "stopped in cycle " << Cycle << " on the way to cycle " << Target
       << (Diverged ? "; the state is as the live run left cycle " +
                          std::to_string(Cycle - 1)
                    : std::string("; the state is as it left it"))
       << "\n";
    return true;
  };
  // Each robot through its own history: forward by a few cycles, on from
  // where it is; else from the copy before (the last one for a cycle past
  // the history, which then runs live).
  for (unsigned K = 0; K < Robots->size(); ++K) {
    BehaviorSession &R = (*Robots)[K];
    CycleHistory &H = *Histories[K];
    uint32_t Now = R.getCycle();
    uint32_t Logged = std::min(Target, H.last());
    if (Target <= Now ||
        (Logged > Now && Logged - Now > H.getSnapshotEvery()))
      restoreFromHistory(K, Logged, /*Before=*/Target <= H.last());
    while (R.getCycle() < Logged) {
      uint32_t Cycle = R.getCycle() + 1;
      bool FromHistory;
      if (Stopped(runRobotCycle(K, FromHistory), Cycle, K))
        return false;
    }
  }
  // Past the history, the team runs live, robot by robot.
  while (S->getCycle() < Target) {
    uint32_t Cycle = S->getCycle() + 1;
    bool FromHistory;
    unsigned Broke;
    BehaviorSession::Outcome O = runNextCycle(FromHistory, Broke);
    if (Stopped(O, Cycle, Broke))
      return false;
  }
  return true;
}

void Repl::showCycle() {
  uint32_t Cycle = S->getCycle();
  OS << cycleName(Cycle, Selected) << ": ";
  if (Cycle == 0)
    OS << "before the first cycle\n";
  else
    OS << debug::formatTraceLine(
              L->Tables, debug::takeSnapshot(S->getState(), &S->getInfo()))
       << "\n";
}

/// Parses a cycle number; false if `Text` is none.
static bool parseCycle(llvm::StringRef Text, uint32_t &Cycle) {
  return !Text.empty() && !Text.getAsInteger(10, Cycle);
}

bool Repl::checkInHistory(long long Cycle, bool Forward, llvm::SMLoc Loc) {
  if (Cycle >= History->first() && (Forward || Cycle <= History->last()))
    return true;
  C->Diags.report(Loc, diag::err_repl_outside_history)
      << Cycle << History->first() << History->last();
  return false;
}

void Repl::cmdGoto(llvm::StringRef Args, llvm::SMLoc Loc) {
  uint32_t Target;
  if (!parseCycle(Args, Target)) {
    C->Diags.report(Loc, diag::err_repl_missing_argument)
        << "goto" << "a cycle number";
    return;
  }
  if (!checkHistory(Loc) || !checkInHistory(Target, /*Forward=*/true, Loc))
    return;
  if (Target > History->last() && Target - History->last() > MaxCycles) {
    C->Diags.report(Loc, diag::err_repl_bad_count)
        << "goto" << MaxCycles << Args;
    return;
  }
  if (travelTo(Target))
    showCycle();
}

void Repl::cmdBack(llvm::StringRef Args, llvm::SMLoc Loc) {
  unsigned N = parseCount("back", Args, 1, Loc);
  if (!N || !checkHistory(Loc))
    return;
  long long Target = (long long)S->getCycle() - N;
  if (!checkInHistory(Target, /*Forward=*/false, Loc))
    return;
  if (travelTo(uint32_t(Target)))
    showCycle();
}

void Repl::cmdHistory(llvm::StringRef Args, llvm::SMLoc Loc) {
  if (Args.empty()) {
    C->Diags.report(Loc, diag::err_repl_missing_argument)
        << "history" << "an expression";
    return;
  }
  if (!checkHistory(Loc))
    return;
  auto [Rest, ToText] = splitCount(Args);
  auto [Text, FromText] = splitCount(Rest);
  uint32_t From = History->first() + 1, To = History->last();
  if (!ToText.empty() && FromText.empty()) {
    C->Diags.report(Loc, diag::err_repl_missing_argument)
        << "history" << "both FROM and TO, or neither";
    return;
  }
  if (!ToText.empty()) {
    // Digits that do not fit a cycle number are no cycle of the history.
    if (!parseCycle(FromText, From) || !parseCycle(ToText, To)) {
      C->Diags.report(Loc, diag::err_repl_missing_argument)
          << "history" << "FROM and TO as cycle numbers";
      return;
    }
    if (!checkInHistory(From, false, Loc) || !checkInHistory(To, false, Loc))
      return;
    if (From > To) {
      C->Diags.report(Loc, diag::err_repl_history_order) << From << To;
      return;
    }
    // The value before the first cycle is the start of the comparison.
    if (From == History->first()) {
      if (From == To) {
        OS << "cycle " << From << " is the history's start; ':history' "
           << "shows the cycles after it\n";
        return;
      }
      ++From;
    }
  }
  if (From > To) {
    // Only the history's first moment: no cycle ran after it.
    OS << "no cycle has run in this history yet\n";
    return;
  }
  std::optional<Probe> P = compileProbe(Text, "history", /*Bool=*/false, Loc);
  if (!P)
    return;
  uint32_t Here = S->getCycle();
  std::optional<llvm::json::Value> Prev;
  unsigned Changes = 0;
  if (travelTo(From - 1) && (Prev = evalProbe(*P))) {
    llvm::json::Value First = *Prev;
    for (uint32_t Cycle = From; Cycle <= To; ++Cycle) {
      if (!travelTo(Cycle))
        break;
      std::optional<llvm::json::Value> Now = evalProbe(*P);
      if (!Now)
        break;
      if (!debug::findDifference(*Prev, *Now, Text))
        continue;
      if (++Changes <= MaxHistoryLines)
        OS << "cycle " << Cycle << ": " << formatValue(P->Result.Ty, *Prev)
           << " -> " << formatValue(P->Result.Ty, *Now) << "\n";
      Prev = std::move(*Now);
    }
    if (Changes > MaxHistoryLines)
      OS << "... and " << Changes - MaxHistoryLines
         << " more changes; ':history EXPR FROM TO' shows a part\n";
    if (!Changes)
      OS << Text << " did not change in cycles " << From << " to " << To
         << "; it is " << formatValue(P->Result.Ty, First) << "\n";
  }
  flushDiagnostics();
  destroyProbe(*P);
  travelTo(Here);
}
