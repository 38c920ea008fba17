//===- Outcome.cpp - what ended a cycle early, as a diagnostic -----------===//
//
// A session's guard (BehaviorSession::Outcome) says a cycle ran out of
// time or crashed and which probe was last passed; this file turns that
// into an error at the loop or the call of registered C++ it names.
//
//===----------------------------------------------------------------------===//
#include "bsc/Run/Run.h"
#include <csignal>
#include <cstring>

using namespace bsc;

/// "SIGSEGV (segmentation fault)".
static std::string describeSignal(int Sig) {
  const char *Name = Sig == SIGSEGV   ? "SIGSEGV"
                     : Sig == SIGBUS  ? "SIGBUS"
                     : Sig == SIGFPE  ? "SIGFPE"
                     : Sig == SIGILL  ? "SIGILL"
                                      : "signal";
  return std::string(Name) + " (" + strsignal(Sig) + ")";
}

bool bsc::reportOutcome(Compilation &C, const LoadedBehavior &L,
                        const BehaviorSession::Outcome &O, uint32_t Cycle,
                        unsigned LimitMs) {
  auto Site = [&](uint32_t N) -> const DebugSite * {
    return N && N <= L.Layout.Sites.size() ? &L.Layout.Sites[N - 1] : nullptr;
  };
  if (O.K != BehaviorSession::Outcome::Completed && O.WorldHook) {
    std::string When = Cycle ? "cycle " + std::to_string(Cycle)
                             : std::string("before the first cycle");
    if (O.K == BehaviorSession::Outcome::TimedOut)
      C.Diags.report(llvm::SMLoc(), diag::err_world_runaway)
          << When << LimitMs << O.WorldHook;
    else
      C.Diags.report(llvm::SMLoc(), diag::err_world_crash)
          << When << describeSignal(O.Signal) << O.WorldHook;
    return false;
  }
  switch (O.K) {
  case BehaviorSession::Outcome::Completed:
    return true;
  case BehaviorSession::Outcome::Diverged:
    C.Diags.report(llvm::SMLoc(), diag::err_cycle_diverged)
        << Cycle << O.Divergence;
    return false;
  case BehaviorSession::Outcome::TimedOut:
    if (const DebugSite *N = Site(O.NativeSite))
      C.Diags.report(N->Loc, diag::err_cycle_runaway_native)
          << Cycle << LimitMs << N->Native;
    else if (const DebugSite *Loop = Site(O.LoopSite))
      C.Diags.report(Loop->Loc, diag::err_cycle_runaway)
          << Cycle << LimitMs << Loop->In->getQualifiedName();
    else // Only C++ the probes do not mark (life-cycle thunks) is left.
      C.Diags.report(llvm::SMLoc(), diag::err_cycle_runaway_native)
          << Cycle << LimitMs << "a constructor or destructor";
    return false;
  case BehaviorSession::Outcome::Crashed:
    if (O.Signal == SIGILL && reportFailedAssertion(C, L, Cycle))
      return false;
    if (const DebugSite *N = Site(O.NativeSite)) {
      C.Diags.report(N->Loc, diag::err_cycle_crash_native)
          << Cycle << describeSignal(O.Signal) << N->Native;
      // The likeliest cause when C++ that reads bs::Context::user() runs
      // without a world: nothing attached a user pointer.
      if (N->TakesContext && O.NullUser)
        C.Diags.report(N->Loc, diag::note_null_user_pointer) << N->Native;
    } else
      C.Diags.report(llvm::SMLoc(), diag::err_cycle_crash_native)
          << Cycle << describeSignal(O.Signal) << "a constructor or destructor";
    return false;
  }
  return true;
}
