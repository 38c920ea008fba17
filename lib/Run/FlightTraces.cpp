//===- FlightTraces.cpp - the trace records of a flight log ----------------===//
//
// A robot's object built with --instrument and --flight-recorder puts each
// cycle's trace record into its flight log (bsc/Run/BinaryLog.h). `bsc
// trace-decode` reads them as it reads a classic trace log: the object's
// tables name the tasks, no behavior and no JIT are needed.
//
//===----------------------------------------------------------------------===//
#include "bsc/Run/Run.h"
#include "llvm/Support/MemoryBuffer.h"

using namespace bsc;

std::optional<std::vector<debug::LoggedCycle>>
bsc::readFlightLogTraces(llvm::StringRef Path, const debug::DebugTables &Tables,
                         DiagnosticEngine &Diags) {
  auto File = llvm::MemoryBuffer::getFile(Path, /*IsText=*/false,
                                          /*RequiresNullTerminator=*/false);
  if (!File) {
    Diags.report(llvm::SMLoc(), diag::err_cannot_open_file)
        << Path << File.getError().message();
    return std::nullopt;
  }
  BinaryLogReader Reader;
  if (!Reader.open((*File)->getBuffer())) {
    Diags.report(llvm::SMLoc(), diag::err_log_damaged)
        << Path << Reader.getError();
    return std::nullopt;
  }
  bool Team = Reader.countRobots() > 1;
  std::vector<debug::LoggedCycle> Cycles;
  BinaryLogCycle C;
  while (Reader.next(C)) {
    if (C.Trace.empty()) {
      Diags.report(llvm::SMLoc(), diag::err_flight_no_trace)
          << Path << C.Cycle;
      return std::nullopt;
    }
    llvm::Expected<debug::LoggedCycle> Logged =
        debug::decodeLoggedCycle(Tables, C.Cycle, C.Trace);
    if (!Logged) {
      Diags.report(llvm::SMLoc(), diag::err_trace_decode)
          << Path << llvm::toString(Logged.takeError());
      return std::nullopt;
    }
    if (Team)
      Logged->Robot = int(C.Robot);
    Cycles.push_back(std::move(*Logged));
  }
  if (Reader.failed()) {
    Diags.report(llvm::SMLoc(), diag::err_log_damaged)
        << Path << Reader.getError();
    return std::nullopt;
  }
  return Cycles;
}
