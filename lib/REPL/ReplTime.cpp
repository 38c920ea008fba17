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
// The copies are of bytes, put back where they were taken: a task local,
// `input` or `output` of a registered class whose destructor frees memory
// (a std::vector inside) turns the history off, and the commands say why.
//
//===----------------------------------------------------------------------===//
#include "ReplImpl.h"
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
  History.reset();
  NoHistory.clear();
  if (Robots->size() > 1) { // :goto, :back and :history say so (oneRobot).
    NoHistory = "it runs a team";
    return;
  }
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
  History = std::make_unique<CycleHistory>(
      CycleHistory::Sizes{S->getInfo().state_size, L->Input.Size,
                          L->Output.Size},
      SnapshotEvery);
  History->reset(S->getCycle(), getBlocks());
  S->keepCalls(true);
}

CycleHistory::Blocks Repl::getBlocks() const {
  return {S->getState(), S->getInput(), S->getOutput()};
}

BehaviorSession::Outcome Repl::runNextCycle(bool &FromHistory) {
  uint32_t Next = S->getCycle() + 1;
  FromHistory = History && Next <= History->last();
  if (!FromHistory) {
    BehaviorSession::Outcome O = S->runCycle(Opts.CycleLimitMs);
    if (O.K == BehaviorSession::Outcome::Completed) {
      recordLiveCycle();
    } else if (History) {
      // A crashed cycle cannot be re-run: its moment is the copy.
      History->recordCycle(S->getLastCalls(), getBlocks());
      History->keepPresent(Next, getBlocks());
    }
    return O;
  }
  if (History->isEdited(Next)) {
    // The prompt changed this moment: it is the copy, not a re-run.
    restoreFromHistory(Next, /*Before=*/false);
    return {};
  }
  History->applyInput(Next, S->getInput());
  CycleRecord Calls;
  History->getCalls(Next, Calls);
  BehaviorSession::Outcome O = S->replayCycle(Opts.CycleLimitMs, Calls);
  if (O.K == BehaviorSession::Outcome::Completed) {
    std::string Why = describeViewDifference(*Values, *L, *S,
                                             History->liveViewAt(Next));
    if (!Why.empty()) {
      O.K = BehaviorSession::Outcome::Diverged;
      O.Divergence = "the re-run differs from the live run: " + Why;
    }
  }
  if (O.K == BehaviorSession::Outcome::Diverged) {
    // Back to the last moment both agree on; what follows is forgotten.
    const std::vector<unsigned char> &View = History->liveViewAt(Next - 1);
    CycleHistory::Blocks B = getBlocks();
    size_t Sizes[3];
    S->getViewSizes(Sizes);
    void *User = bs_state_user(B.State);
    std::memcpy(B.State, View.data(), Sizes[0]);
    bs_state_set_user(B.State, User);
    if (Sizes[1])
      std::memcpy(B.Input, View.data() + Sizes[0], Sizes[1]);
    if (Sizes[2])
      std::memcpy(B.Output, View.data() + Sizes[0] + Sizes[1], Sizes[2]);
    History->keepPresent(Next - 1, B);
  }
  return O;
}

uint32_t Repl::restoreFromHistory(uint32_t Cycle, bool Before) {
  // The user pointer is the session's (its world set it, perhaps after the
  // copy was taken), not the moment's.
  void *User = bs_state_user(S->getState());
  uint32_t At = History->restore(Cycle, Before, getBlocks());
  bs_state_set_user(S->getState(), User);
  return At;
}

void Repl::recordLiveCycle() {
  if (History)
    History->recordCycle(S->getLastCalls(), getBlocks());
}

void Repl::forgetFuture() {
  if (History && S->getCycle() < History->last())
    History->keepPresent(S->getCycle(), getBlocks());
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
  if (History && copyBlocks() != Before)
    History->keepPresent(S->getCycle(), getBlocks());
}

bool Repl::checkHistory(llvm::SMLoc Loc) {
  if (History)
    return true;
  C->Diags.report(Loc, diag::err_repl_no_history) << NoHistory;
  return false;
}

bool Repl::travelTo(uint32_t Target) {
  uint32_t Now = S->getCycle();
  // Forward by a few cycles: on from here. Else from the copy before (the
  // last one for a cycle past the history, which then runs live).
  uint32_t Logged = std::min(Target, History->last());
  if (Target <= Now || (Logged > Now &&
                        Logged - Now > History->getSnapshotEvery()))
    restoreFromHistory(Logged, /*Before=*/Target <= History->last());
  while (S->getCycle() < Target) {
    uint32_t Cycle = S->getCycle() + 1;
    bool FromHistory;
    BehaviorSession::Outcome O = runNextCycle(FromHistory);
    if (!reportOutcome(*C, *L, O, Cycle, Opts.CycleLimitMs)) {
      bool Diverged = O.K == BehaviorSession::Outcome::Diverged;
      if (Diverged)
        C->Diags.report(llvm::SMLoc(), diag::note_history_ends) << Cycle - 1;
      flushDiagnostics();
      OS << "stopped in cycle " << Cycle << " on the way to cycle " << Target
         << (Diverged ? "; the state is as the live run left cycle " +
                            std::to_string(Cycle - 1)
                      : std::string("; the state is as it left it"))
         << "\n";
      return false;
    }
  }
  return true;
}

void Repl::showCycle() {
  uint32_t Cycle = S->getCycle();
  OS << "cycle " << Cycle << ": ";
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
  if (!oneRobot(":goto", Loc))
    return;
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
  if (!oneRobot(":back", Loc))
    return;
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
  if (!oneRobot(":history", Loc))
    return;
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
