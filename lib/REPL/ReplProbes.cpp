//===- ReplProbes.cpp - expressions evaluated between cycles --------------===//
//
// A probe is a REPL line compiled once into a function that writes its
// value to a slot, then run under the session's guard whenever it is
// asked: after each cycle for a watch, a breakpoint's condition and
// `:until` (ReplBreakpoints.cpp), at each cycle of the past for `:history`
// (ReplTime.cpp).
//
//===----------------------------------------------------------------------===//
#include "ReplImpl.h"
#include "llvm/ADT/StringExtras.h"

using namespace bsc;
using namespace bsc::repl;

std::optional<Probe> Repl::compileProbe(llvm::StringRef Text,
                                        llvm::StringRef Cmd, bool Bool,
                                        llvm::SMLoc Loc) {
  std::optional<CompiledLine> R = compileLine(Text);
  if (!R)
    return std::nullopt;
  if (!R->Result.Ptr || (Bool && !R->Result.Ty->isBool())) {
    if (Bool)
      C->Diags.report(Loc, diag::err_repl_not_a_condition)
          << Cmd << Text
          << (R->Result.Ptr ? R->Result.Ty->getName() : "void");
    else
      C->Diags.report(Loc, diag::err_repl_watch_void) << Cmd;
    destroySlot(R->Result);
    return std::nullopt;
  }
  return Probe{Text.str(), R->Fn, R->Result};
}

std::optional<llvm::json::Value> Repl::evalProbe(Probe &P) {
  BehaviorSession::Outcome O = S->runGuarded(P.Eval, Opts.CycleLimitMs);
  if (!reportOutcome(*C, *L, O, S->getCycle(), Opts.CycleLimitMs))
    return std::nullopt;
  return Values->read(P.Result.Ty, P.Result.Ptr);
}

bool Repl::isTrue(Probe &P) {
  std::optional<llvm::json::Value> V = evalProbe(P);
  return V && V->getAsBoolean().value_or(false);
}

std::pair<llvm::StringRef, llvm::StringRef>
bsc::repl::splitCount(llvm::StringRef Args) {
  auto [Head, Last] = Args.rsplit(' ');
  Head = Head.rtrim();
  if (Last.empty() || Head.empty() || !llvm::all_of(Last, llvm::isDigit) ||
      llvm::StringRef("=<>!+-*/%&|(,").contains(Head.back()))
    return {Args, ""};
  return {Head, Last};
}
