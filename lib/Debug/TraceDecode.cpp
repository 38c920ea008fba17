//===- TraceDecode.cpp - a robot's trace log as trace lines ---------------===//
#include "bsc/Debug/TraceDecode.h"
#include "bsc/CodeGen/CodeGen.h"
#include "bsc/Debug/Trace.h"
#include "llvm/Object/ObjectFile.h"
#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/raw_ostream.h"
#include <optional>

using namespace bsc;
using namespace bsc::debug;

/// The JSON text of the object's DebugTablesSection; std::nullopt without
/// one. Reports an unreadable object or section and returns false.
static bool readTablesText(const TraceDecodeOptions &Opts,
                           DiagnosticEngine &Diags,
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
          << Opts.ObjectPath << llvm::toString(Contents.takeError());
      return false;
    }
    Text = Contents->split('\0').first;
  }
  return true;
}

bool debug::decodeTraceLog(const TraceDecodeOptions &Opts,
                           DiagnosticEngine &Diags, llvm::raw_ostream &OS) {
  auto Fail = [&](const std::string &Path, const std::string &Why) {
    Diags.report(llvm::SMLoc(), diag::err_trace_decode) << Path << Why;
    return false;
  };
  auto Obj = llvm::object::ObjectFile::createObjectFile(Opts.ObjectPath);
  if (!Obj)
    return Fail(Opts.ObjectPath, llvm::toString(Obj.takeError()));
  std::optional<llvm::StringRef> Text;
  if (!readTablesText(Opts, Diags, *Obj->getBinary(), Text))
    return false;
  if (!Text) {
    Diags.report(llvm::SMLoc(), diag::err_no_debug_tables) << Opts.ObjectPath;
    return false;
  }
  llvm::Expected<DebugTables> Tables = parseDebugTables(*Text);
  if (!Tables)
    return Fail(Opts.ObjectPath, llvm::toString(Tables.takeError()));
  auto Log = llvm::MemoryBuffer::getFile(Opts.LogPath, /*IsText=*/false,
                                         /*RequiresNullTerminator=*/false);
  if (!Log)
    return Fail(Opts.LogPath, Log.getError().message());
  auto Cycles = parseTraceLog((*Log)->getBuffer(), *Tables);
  if (!Cycles)
    return Fail(Opts.LogPath, llvm::toString(Cycles.takeError()));
  TraceFilter Traces(Opts.OnlyChanges ? TraceMode::Changes
                                      : TraceMode::EveryCycle);
  for (const LoggedCycle &Cycle : *Cycles) {
    std::string Trace = formatTraceLine(*Tables, Cycle.Records);
    if (Traces.shouldPrint(Trace))
      OS << "cycle " << Cycle.Cycle << ": " << Trace << "\n";
    // Printed whether or not its cycle's line is: it names the cycle.
    std::string Budget = formatBudgetLine(*Tables, Cycle);
    if (!Budget.empty())
      OS << Budget << "\n";
  }
  return true;
}
