//===- VerifyCommand.cpp - `bsc verify`'s options, then lib/Verify -------===//
#include "bsc/Driver/Driver.h"
#include "bsc/Verify/Verify.h"
#include "llvm/Support/raw_ostream.h"

using namespace bsc;

int bsc::verifyCommand(Compilation &C, const FrontendOptions &FOpts,
                       const VerifyCommandOptions &Opts) {
  VerifyOptions V;
  bool OK = true;
  if (FOpts.Inputs.empty()) {
    C.Diags.report(llvm::SMLoc(), diag::err_no_input_files);
    OK = false;
  }
  if (!Opts.Cycles ||
      llvm::StringRef(*Opts.Cycles).getAsInteger(10, V.Cycles) ||
      V.Cycles == 0 || V.Cycles > MaxVerifyCycles) {
    C.Diags.report(llvm::SMLoc(), diag::err_verify_cycles)
        << MaxVerifyCycles << Opts.Cycles.value_or("");
    OK = false;
  }
  if (Opts.LoopLimit &&
      (llvm::StringRef(*Opts.LoopLimit).getAsInteger(10, V.LoopLimit) ||
       V.LoopLimit == 0 || V.LoopLimit > MaxLoopLimit)) {
    C.Diags.report(llvm::SMLoc(), diag::err_verify_loop_limit)
        << MaxLoopLimit << *Opts.LoopLimit;
    OK = false;
  }
  if (Opts.SolverTimeout &&
      (llvm::StringRef(*Opts.SolverTimeout).getAsInteger(10, V.SolverTimeout) ||
       V.SolverTimeout == 0 || V.SolverTimeout > MaxSolverTimeout)) {
    C.Diags.report(llvm::SMLoc(), diag::err_verify_solver_timeout)
        << MaxSolverTimeout << *Opts.SolverTimeout;
    OK = false;
  }
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
