//===- Repl.h - `bsc repl` -------------------------------------*- C++ -*-===//
//
// The interactive debugger of docs/repl.md: step a behavior cycle by cycle,
// look at its tasks, set its input, evaluate b-script between cycles, stop
// at breakpoints, record and replay, reload edited files.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_REPL_REPL_H
#define BSC_REPL_REPL_H

#include "bsc/Run/Run.h"

namespace bsc {

struct ReplOptions {
  FrontendOptions Frontend;
  LoadOptions Load;
  std::string EntryName = "main";
  std::string BatchFile; ///< --batch: read the lines from this file.
  std::string WorldLibrary; ///< --world: feeds input, reads output.
  std::string WorldOutput;  ///< --world-output: what the world prints.
  unsigned Robots = 1;      ///< --robots N: a team, stepped together.
  unsigned CycleLimitMs = DefaultCycleLimitMs;
};

/// Loads the behavior and reads lines: from --batch, else from a standard
/// input that is not a terminal, else at a prompt with history and
/// completion. Answers on `OS`; diagnostics go to stderr. Returns the exit
/// status: 1 if the behavior cannot be loaded, else 0 (mistakes at the
/// prompt are reported and the session goes on).
int runRepl(const ReplOptions &Opts, llvm::raw_ostream &OS);

} // namespace bsc

#endif
