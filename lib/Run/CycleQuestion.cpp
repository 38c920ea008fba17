//===- CycleQuestion.cpp - `bsc replay --find`: a question of every cycle -===//
#include "CycleQuestion.h"
#include "bsc/CodeGen/CodeGen.h"

using namespace bsc;

std::unique_ptr<CycleQuestion>
CycleQuestion::compile(Compilation &C, LoadedBehavior &L,
                       llvm::StringRef Text, unsigned Lasting) {
  std::unique_ptr<CycleQuestion> Q(
      new CycleQuestion(L, Text.str(), std::max(Lasting, 1u)));
  for (unsigned T = 0; T < L.Tables.Tasks.size(); ++T)
    if (Text.trim() == L.Tables.Tasks[T].Name ||
        Text.trim() == L.Tables.Tasks[T].ShortName) {
      Q->Task = T;
      Q->Text = L.Tables.Tasks[T].Name;
      return Q;
    }
  Q->Checker = makeLineChecker(C, L);
  unsigned Number = 1;
  std::optional<CompiledLine> Whole = compileLine(
      C, L, *Q->Checker, Text, "--find", Number++, Q->Variables);
  if (!Whole)
    return nullptr;
  Q->Whole = std::move(*Whole);
  const VarDecl *Result = Q->Whole.Checked->Result;
  if (!Result || !Result->Ty->isBool() || !Result->Init) {
    C.Diags.report(llvm::SMLoc(), diag::err_replay_find_not_bool)
        << Text
        << (Result ? Result->Ty->getName().str() : std::string("a statement"));
    return nullptr;
  }
  // Its parts, but the whole: each a line of its own, as printed.
  std::vector<ExpressionPart> Parts = listExpressionParts(*Result->Init);
  bool WholeIsPart = !Parts.empty() && Parts.front().E == Result->Init;
  std::vector<unsigned> Depth;
  for (const ExpressionPart &P : Parts) {
    Depth.push_back(P.Parent < 0 ? 0 : Depth[P.Parent] + 1);
    if (P.E == Result->Init)
      continue;
    std::optional<CompiledLine> Line = compileLine(
        C, L, *Q->Checker, P.Text, "--find", Number++, Q->Variables);
    if (!Line) // Printed from the tree, a part reads back; if not, none.
      return nullptr;
    Q->Parts.push_back(
        {P.Text, Depth.back() - unsigned(WholeIsPart), std::move(*Line)});
  }
  return Q;
}

CycleQuestion::~CycleQuestion() {
  destroySlot(&L, Whole.Result);
  for (Part &P : Parts)
    destroySlot(&L, P.Line.Result);
  for (Slot &V : Variables)
    destroySlot(&L, V);
}

void CycleQuestion::startLog() {
  Stretches.clear();
  Open.clear();
  Found = false;
}

std::string CycleQuestion::describeParts(BehaviorSession &S,
                                         unsigned LimitMs) {
  std::string Text;
  if (Task) {
    for (const debug::Activation &A :
         debug::takeSnapshot(S.getState(), &S.getInfo()))
      if (A.Task == *Task)
        Text = " [" + debug::describeActivation(L.Tables, A) + "]";
    return Text;
  }
  for (Part &P : Parts) {
    Text += "\n      " + std::string(2 * P.Depth, ' ') + P.Text;
    // On its own: a part the whole would not have reached (`x != 0 && 10
    // / x > 1`) may trap here.
    if (!P.Line.Result.Ptr ||
        S.runGuarded(P.Line.Fn, LimitMs).K !=
            BehaviorSession::Outcome::Completed) {
      Text += ": not evaluated";
      continue;
    }
    Text += " = " + debug::formatValue(P.Line.Result.Ty,
                                       Values.read(P.Line.Result.Ty,
                                                   P.Line.Result.Ptr));
  }
  return Text;
}

std::optional<bool> CycleQuestion::holds(Compilation &C, BehaviorSession &S) {
  if (Task)
    return llvm::any_of(
        debug::takeSnapshot(S.getState(), &S.getInfo()),
        [&](const debug::Activation &A) { return A.Task == *Task; });
  BehaviorSession::Outcome O = S.runGuarded(Whole.Fn, DefaultCycleLimitMs);
  if (!reportOutcome(C, L, O, S.getCycle(), DefaultCycleLimitMs)) {
    C.Diags.report(llvm::SMLoc(), diag::note_replay_find_stopped) << Text;
    return std::nullopt;
  }
  return *static_cast<const uint8_t *>(Whole.Result.Ptr) != 0;
}

bool CycleQuestion::ask(Compilation &C, unsigned K, BehaviorSession &S) {
  Found = false;
  if (Open.size() <= K)
    Open.resize(K + 1, -1);
  std::optional<bool> Holds = holds(C, S);
  if (!Holds)
    return false;
  uint32_t Cycle = S.getCycle();
  if (!*Holds) {
    Open[K] = -1; // One too short to count is left out at the end.
    return true;
  }
  if (Open[K] < 0) {
    Open[K] = int(Stretches.size());
    Stretches.push_back(
        {K, Cycle, Cycle, describeParts(S, DefaultCycleLimitMs)});
  }
  Stretch &St = Stretches[Open[K]];
  St.Last = Cycle;
  Found = St.Last - St.First + 1 == Lasting;
  return true;
}

std::string CycleQuestion::finishLog(unsigned &Count) {
  std::string Out;
  Count = 0;
  for (const Stretch &St : Stretches) {
    if (St.Last - St.First + 1 < Lasting)
      continue;
    ++Count;
    Out += "  ";
    if (Open.size() > 1) // A team's log.
      Out += "robot " + std::to_string(St.Robot) + ", ";
    if (St.First == St.Last)
      Out += "cycle " + std::to_string(St.First);
    else
      Out += "cycles " + std::to_string(St.First) + " to " +
             std::to_string(St.Last) + " (" +
             std::to_string(St.Last - St.First + 1) + " cycles)";
    Out += ": " + Text + St.Parts + "\n";
  }
  return Out;
}
