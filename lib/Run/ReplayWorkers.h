//===- ReplayWorkers.h - `bsc replay --jobs N`: one process per core -*- C++ -*-===//
//
// The behavior is compiled once in the parent; N forked workers share its
// JIT code (copy-on-write) and take the logs one at a time from a counter
// in shared memory, so a long log does not hold up a whole slice. Each
// worker sends what each log gave (LogResult) through its pipe; the parent
// puts the results in sorted log order, whatever order the workers finish
// in, so that the output does not depend on --jobs.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_LIB_RUN_REPLAYWORKERS_H
#define BSC_LIB_RUN_REPLAYWORKERS_H

#include "bsc/Run/Run.h"
#include <map>
#include <string>
#include <vector>

namespace bsc {

/// What replaying one log gave. A worker sends it to the parent as a
/// record of tagged fields (ReplayWorkers.cpp, "Records"): a new member
/// needs a tag, a line in encodeResult and a case in decodeResult, and an
/// older parent skips tags it does not know.
struct LogResult {
  bool Passed = false;
  /// Replayed exactly (RunOptions::ReplayedExactly), not in regression
  /// mode.
  bool Exact = false;
  uint32_t Cycles = 0;
  double Seconds = 0;
  /// Its diagnostics, as bsc prints them.
  std::string Report;
  /// A failure's way (failureGroup in ReplayLogs.cpp): logs that fail
  /// alike have the same.
  std::string Group;
  /// --update: the log was recorded again; the cycles whose recorded
  /// output differed, per output member.
  bool Updated = false;
  std::map<std::string, unsigned> Changed;
  /// --find: the stretches in which the question held, a line each, and
  /// how many.
  std::string Found;
  uint32_t Stretches = 0;
  /// From a worker: the coverage counters the log added (readCoverage's
  /// order); empty in bsc's own process, whose JIT keeps the sum.
  std::vector<uint64_t> Coverage;
};

/// Replays one log in a fresh session of `L`; an llvm::Error is internal.
using ReplayOneFn = llvm::function_ref<llvm::Expected<LogResult>(size_t Log)>;
/// Called in log order with each log's result as soon as it and every
/// earlier log are known.
using LogDoneFn = llvm::function_ref<void(size_t Log, const LogResult &)>;

/// Replays `NumLogs` logs in `Jobs` (>= 2) forked workers, each log with
/// `ReplayOne` in a worker. A worker that dies fails the log it was
/// replaying (and, if every worker died, the logs none took) with a
/// message built by `Died` from the worker's fate ("was killed by signal
/// 9 (Killed)"). Returns the results in log order; an llvm::Error is
/// internal (no pipe or process could be made).
llvm::Expected<std::vector<LogResult>>
replayInWorkers(size_t NumLogs, unsigned Jobs, ReplayOneFn ReplayOne,
                llvm::function_ref<LogResult(llvm::StringRef Fate)> Died,
                LogDoneFn Done);

/// The workers' records, for the unit test and the parent.
std::string encodeResult(const LogResult &R);
/// False if `Payload` is not a well-formed record.
bool decodeResult(llvm::StringRef Payload, LogResult &R);

} // namespace bsc

#endif
