//===- ReplWhy.cpp - `:why`: the conditions a task evaluated --------------===//
//
// `:why [TASK]` shows the way each task went in the last cycle: every `if`
// and `for` condition it evaluated (or a func it called did), with the
// values of the condition's sub-expressions as the cycle computed them,
// and the yield its call stopped at or how it ended (explainLastCycle,
// lib/Run/Why.cpp).
//
//===----------------------------------------------------------------------===//
#include "ReplImpl.h"

using namespace bsc;
using namespace bsc::repl;

void Repl::cmdWhy(llvm::StringRef Args, llvm::SMLoc Loc) {
  // The entry may be a func: its conditions have no task around them.
  bool EntryIsFunc = !llvm::isa<TaskDecl>(L->Entry);
  std::optional<int> Wanted;
  if (!Args.empty()) {
    if (std::optional<unsigned> T = findTask(Args))
      Wanted = int(*T);
    else if (EntryIsFunc && (Args == L->Entry->getName().Name ||
                             Args == L->Entry->getQualifiedName()))
      Wanted = -1;
    else {
      C->Diags.report(Loc, diag::err_repl_unknown_task) << Args;
      return;
    }
  }
  uint32_t Cycle = S->getCycle();
  std::string Text;
  llvm::raw_string_ostream Why(Text);
  // The JIT's log is of the last robot's cycle; each robot's is kept (none
  // kept: a log of no cycle, which is not this one's).
  static const ExplainLogHeader NoLog{};
  const ExplainLogHeader *Log = nullptr;
  if (!ExplainLogs.empty())
    Log = ExplainLogs[Selected].empty()
              ? &NoLog
              : reinterpret_cast<const ExplainLogHeader *>(
                    ExplainLogs[Selected].data());
  switch (explainLastCycle(*L, *Values, *S, Wanted, Why, Log)) {
  case WhyOutcome::NoCycle:
    OS << "no cycle has run yet\n";
    return;
  case WhyOutcome::NotRecorded:
    OS << "the conditions of " << cycleName(Cycle, Selected)
       << " were not recorded: the behavior was reloaded, or its state put "
          "back, after it ran\n";
    return;
  case WhyOutcome::DidNotRun:
    OS << (*Wanted < 0 ? L->Entry->getName().Name.str()
                       : L->Tables.Tasks[*Wanted].ShortName)
       << " did not run in " << cycleName(Cycle, Selected) << "\n";
    return;
  case WhyOutcome::Printed:
    OS << cycleName(Cycle, Selected) << ":\n" << Text;
    return;
  }
}
