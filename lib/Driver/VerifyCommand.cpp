//===- VerifyCommand.cpp - `bsc verify`'s options, then lib/Verify -------===//
#include "bsc/Driver/Driver.h"
#include "bsc/Verify/Verify.h"
#include "llvm/Support/raw_ostream.h"

using namespace bsc;

/// A count option of 1 to `Max` into `Into` (left as it is if not given);
/// false after reporting `Diag` if it is not one.
static bool readCount(Compilation &C, const std::optional<std::string> &Given,
                      unsigned Max, unsigned &Into, diag::Kind Diag) {
  if (!Given)
    return true;
  if (!llvm::StringRef(*Given).getAsInteger(10, Into) && Into != 0 &&
      Into <= Max)
    return true;
  C.Diags.report(llvm::SMLoc(), Diag) << Max << *Given;
  return false;
}

int bsc::verifyCommand(Compilation &C, const FrontendOptions &FOpts,
                       const VerifyCommandOptions &Opts) {
  VerifyOptions V;
  bool OK = true;
  if (FOpts.Inputs.empty()) {
    C.Diags.report(llvm::SMLoc(), diag::err_no_input_files);
    OK = false;
  }
  // --cycles is required: without it, the message names ''.
  OK &= readCount(C, Opts.Cycles.value_or(""), MaxVerifyCycles, V.Cycles,
                  diag::err_verify_cycles);
  OK &= readCount(C, Opts.LoopLimit, MaxLoopLimit, V.LoopLimit,
                  diag::err_verify_loop_limit);
  OK &= readCount(C, Opts.SolverTimeout, MaxSolverTimeout, V.SolverTimeout,
                  diag::err_verify_solver_timeout);
  if (!OK || !runFrontend(C, FOpts))
    return finishCompilation(C);
  V.EntryName = Opts.EntryName;
  V.CounterexamplePath = Opts.CounterexamplePath;
  V.Load.StandardModules = FOpts.StandardModules;
  V.Load.BindObjects = FOpts.BindObjects;
  VerifyResult R = verifyBehavior(C, V, llvm::outs());
  int Status = finishCompilation(C);
  // Not fully explored is no proof and no counterexample: status 2.
  return R == VerifyResult::NotExplored ? 2 : Status;
}
