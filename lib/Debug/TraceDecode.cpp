//===- TraceDecode.cpp - a robot's trace log as trace lines ---------------===//
#include "bsc/Debug/TraceDecode.h"
#include "bsc/AST/Layout.h"
#include "bsc/Basic/ByteCoding.h"
#include "bsc/Debug/Trace.h"
#include "llvm/Object/ObjectFile.h"
#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/raw_ostream.h"
#include <optional>

using namespace bsc;
using namespace bsc::debug;

/// The JSON text of the object's DebugTablesSection; std::nullopt without
/// one. Reports an unreadable object or section and returns false.
static bool readTablesText(llvm::StringRef ObjectPath, DiagnosticEngine &Diags,
                           llvm::object::ObjectFile &Obj,
                           std::optional<llvm::StringRef> &Text) {
  for (const llvm::object::SectionRef &Sec : Obj.sections()) {
    llvm::Expected<llvm::StringRef> Name = Sec.getName();
    if (!Name) {
      llvm::consumeError(Name.takeError());
      continue;
    }
    if (*Name != DebugTablesSection)
      continue;
    llvm::Expected<llvm::StringRef> Contents = Sec.getContents();
    if (!Contents) {
      Diags.report(llvm::SMLoc(), diag::err_trace_decode)
          << ObjectPath << llvm::toString(Contents.takeError());
      return false;
    }
    Text = Contents->split('\0').first;
  }
  return true;
}

static bool fail(DiagnosticEngine &Diags, llvm::StringRef Path,
                 const std::string &Why) {
  Diags.report(llvm::SMLoc(), diag::err_trace_decode) << Path << Why;
  return false;
}

std::optional<DebugTables> debug::readObjectTables(llvm::StringRef ObjectPath,
                                                   DiagnosticEngine &Diags) {
  auto Obj = llvm::object::ObjectFile::createObjectFile(ObjectPath);
  if (!Obj) {
    fail(Diags, ObjectPath, llvm::toString(Obj.takeError()));
    return std::nullopt;
  }
  std::optional<llvm::StringRef> Text;
  if (!readTablesText(ObjectPath, Diags, *Obj->getBinary(), Text))
    return std::nullopt;
  if (!Text) {
    Diags.report(llvm::SMLoc(), diag::err_no_debug_tables) << ObjectPath;
    return std::nullopt;
  }
  llvm::Expected<DebugTables> Tables = parseDebugTables(*Text);
  if (!Tables) {
    fail(Diags, ObjectPath, llvm::toString(Tables.takeError()));
    return std::nullopt;
  }
  return std::move(*Tables);
}

std::optional<std::vector<LoggedCycle>>
debug::readTraceLog(llvm::StringRef LogPath, const DebugTables &Tables,
                    DiagnosticEngine &Diags) {
  auto Log = llvm::MemoryBuffer::getFile(LogPath, /*IsText=*/false,
                                         /*RequiresNullTerminator=*/false);
  if (!Log) {
    fail(Diags, LogPath, Log.getError().message());
    return std::nullopt;
  }
  auto Cycles = parseTraceLog((*Log)->getBuffer(), Tables);
  if (!Cycles) {
    fail(Diags, LogPath, llvm::toString(Cycles.takeError()));
    return std::nullopt;
  }
  return std::move(*Cycles);
}

bool debug::decodeTraceLog(const TraceDecodeOptions &Opts,
                           DiagnosticEngine &Diags, llvm::raw_ostream &OS) {
  std::optional<DebugTables> Tables = readObjectTables(Opts.ObjectPath, Diags);
  if (!Tables)
    return false;
  std::optional<std::vector<LoggedCycle>> Cycles =
      isBinaryLogFile(Opts.LogPath) && Opts.ReadFlightLog
          ? Opts.ReadFlightLog(Opts.LogPath, *Tables, Diags)
          : readTraceLog(Opts.LogPath, *Tables, Diags);
  if (!Cycles)
    return false;
  // --changes per robot: each robot's line against its own before.
  std::vector<TraceFilter> Traces;
  for (const LoggedCycle &Cycle : *Cycles) {
    size_t K = Cycle.Robot < 0 ? 0 : size_t(Cycle.Robot);
    while (Traces.size() <= K)
      Traces.emplace_back(Opts.OnlyChanges ? TraceMode::Changes
                                           : TraceMode::EveryCycle);
    std::string Trace = formatTraceLine(*Tables, Cycle.Records);
    if (Traces[K].shouldPrint(Trace))
      OS << "cycle " << Cycle.Cycle
         << (Cycle.Robot < 0 ? "" : ", robot " + std::to_string(Cycle.Robot))
         << ": " << Trace << "\n";
    // Printed whether or not its cycle's line is: it names the cycle.
    std::string Budget = formatBudgetLine(*Tables, Cycle);
    if (!Budget.empty())
      OS << Budget << "\n";
  }
  return true;
}
