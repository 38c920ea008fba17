//===- TraceDecode.h - a robot's trace log as trace lines ------*- C++ -*-===//
//
// `bsc trace-decode`: an object compiled with --instrument carries the
// debugger's tables (DebugTablesSection); a robot's log carries one trace
// record per cycle (bscript.h, "Trace logs"). Together they give the lines
// `bsc run --trace` prints, without the behavior's sources or a JIT.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_DEBUG_TRACEDECODE_H
#define BSC_DEBUG_TRACEDECODE_H

#include "bsc/Basic/Diagnostic.h"
#include "bsc/Debug/Trace.h"
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace llvm {
class raw_ostream;
}

namespace bsc::debug {

struct TraceDecodeOptions {
  /// --object: the instrumented object holding the tables.
  std::string ObjectPath;
  /// The robot's trace log.
  std::string LogPath;
  /// --changes: only the cycles whose line differs from the one before.
  bool OnlyChanges = false;
  /// Set by the driver: reads the trace records of a flight log (a
  /// binary log, bsc/Run/BinaryLog.h, which this library does not read);
  /// reports and returns std::nullopt.
  std::function<std::optional<std::vector<LoggedCycle>>(
      llvm::StringRef Path, const DebugTables &Tables,
      DiagnosticEngine &Diags)>
      ReadFlightLog;
};

/// Prints each cycle of the log (a robot's trace log, or the trace records
/// of a flight log) as `cycle N: <trace line>` (`cycle N, robot K:` in a
/// team's) to `OS`, with the cycle's budget line if a loop ran out of it. Reports an unreadable
/// object or log, an object without tables and a malformed log into
/// `Diags` and returns false.
bool decodeTraceLog(const TraceDecodeOptions &Opts, DiagnosticEngine &Diags,
                    llvm::raw_ostream &OS);

/// The tables an instrumented object embeds; reports an unreadable object
/// or one without tables and returns std::nullopt.
std::optional<DebugTables> readObjectTables(llvm::StringRef ObjectPath,
                                            DiagnosticEngine &Diags);
/// A robot's trace log read with `Tables`; reports an unreadable or
/// malformed log (naming the byte and the cycle) and returns std::nullopt.
std::optional<std::vector<LoggedCycle>>
readTraceLog(llvm::StringRef LogPath, const DebugTables &Tables,
             DiagnosticEngine &Diags);

} // namespace bsc::debug

#endif
