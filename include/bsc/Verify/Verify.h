//===- Verify.h - `bsc verify`: assertions for every input ------*- C++ -*-===//
//
// Bounded model checking of a behavior's assertions (docs/verify.md): the
// cycle the JIT runs, compiled with AssertionMode::Verify and optimised
// into one function, is encoded cycle after cycle (lib/Verify/Encoder.h)
// from the state the JIT starts with, each cycle's `input` free but for
// the behavior's `assume`s; Z3 looks for the first cycle in which an
// assertion can fail, and tries k-induction. Registered C++ returns any
// value, unless a model (a b-script func, lib/Verify/Models.h) says more.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_VERIFY_VERIFY_H
#define BSC_VERIFY_VERIFY_H

#include "bsc/Run/Run.h"

namespace bsc {

/// --loop-limit's default and largest value.
constexpr unsigned DefaultLoopLimit = 16, MaxLoopLimit = 256;
/// --solver-timeout's default and largest value, in seconds.
constexpr unsigned DefaultSolverTimeout = 600, MaxSolverTimeout = 86400;

struct VerifyOptions {
  std::string EntryName = "main";
  unsigned Cycles = 0;      ///< --cycles N (required).
  /// --loop-limit: the passes of each loop followed in one cycle.
  unsigned LoopLimit = DefaultLoopLimit;
  /// --solver-timeout: the seconds one question to the solver may take
  /// before the result is "not fully explored".
  unsigned SolverTimeout = DefaultSolverTimeout;
  std::string CounterexamplePath; ///< -o: a recording of the counterexample.
  LoadOptions Load;         ///< The standard modules and --bind objects.
};

/// The most cycles --cycles takes.
constexpr unsigned MaxVerifyCycles = 1000;

enum class VerifyResult { Verified, Counterexample, NotExplored, Error };

/// Verifies `C.Checked` (the front end ran) and prints the result to `OS`;
/// a counterexample, or what was not explored, is an error in C.Diags.
VerifyResult verifyBehavior(Compilation &C, const VerifyOptions &Opts,
                            llvm::raw_ostream &OS);

} // namespace bsc

#endif
