//===- ReplayLogs.cpp - `bsc replay`: many recorded runs, one compile -----===//
//
// The behavior is compiled once; each recording under the folder is then
// replayed in a fresh session (its own state, as a robot starts), one
// after the other. A log passes when every recorded output matches; a
// damaged or failing log fails alone, with its diagnostics, and the others
// still run. `--shard K/N` takes every N-th log from the K-th of the
// sorted list, so that N machines together replay each log once.
//
//===----------------------------------------------------------------------===//
#include "bsc/Run/Run.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/Path.h"
#include "llvm/Support/ToolOutputFile.h"
#include "llvm/Support/raw_ostream.h"
#include <chrono>

using namespace bsc;

namespace {
/// What replaying one log gave.
struct LogResult {
  std::string Path;
  bool Passed = false;
  uint32_t Cycles = 0;
  double Seconds = 0;
  /// Its diagnostics, as bsc prints them.
  std::string Report;
};
} // namespace

/// The `.jsonl` files under `Dir`, sorted; false after reporting a folder
/// that cannot be read.
static bool findLogs(Compilation &C, llvm::StringRef Dir,
                     std::vector<std::string> &Logs) {
  if (!llvm::sys::fs::is_directory(Dir)) {
    C.Diags.report(llvm::SMLoc(), diag::err_replay_logs_not_folder) << Dir;
    return false;
  }
  std::error_code EC;
  for (llvm::sys::fs::recursive_directory_iterator It(Dir, EC), End;
       It != End && !EC; It.increment(EC))
    if (llvm::sys::path::extension(It->path()) == ".jsonl" &&
        It->type() != llvm::sys::fs::file_type::directory_file)
      Logs.push_back(It->path());
  if (EC) {
    C.Diags.report(llvm::SMLoc(), diag::err_cannot_open_file)
        << Dir << EC.message();
    return false;
  }
  llvm::sort(Logs);
  return true;
}

/// Replays one log in a fresh session of `L`; an llvm::Error is internal.
static llvm::Expected<LogResult> replayOne(Compilation &C, LoadedBehavior &L,
                                           const ReplayLogsOptions &Opts,
                                           const std::string &Path) {
  LogResult R;
  R.Path = Path;
  auto Start = std::chrono::steady_clock::now();
  auto S = startSession(C, L);
  if (!S)
    return S.takeError();
  if (*S) {
    RunOptions Run;
    Run.ReplayPath = Path;
    Run.CycleLimitMs = Opts.CycleLimitMs;
    R.Passed = runBehavior(C, L, **S, Run, llvm::nulls()) &&
               !C.Diags.hasErrors();
    R.Cycles = (*S)->getCycle();
  }
  R.Seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                            Start)
                  .count();
  llvm::raw_string_ostream OS(R.Report);
  printDiagnostics(C.SM, C.Diags.getDiagnostics(), OS);
  C.Diags.clear();
  return R;
}

/// `--junit FILE`: one test case per log, for CI systems.
static bool writeJUnit(Compilation &C, llvm::StringRef Path,
                       const std::vector<LogResult> &Results) {
  std::error_code EC;
  llvm::ToolOutputFile Out(Path, EC, llvm::sys::fs::OF_Text);
  if (EC) {
    C.Diags.report(llvm::SMLoc(), diag::err_cannot_write_output)
        << Path << EC.message();
    return false;
  }
  auto Escape = [](llvm::StringRef S) {
    std::string E;
    for (char Ch : S)
      E += Ch == '<'    ? "&lt;"
           : Ch == '>'  ? "&gt;"
           : Ch == '&'  ? "&amp;"
           : Ch == '"'  ? "&quot;"
           : (unsigned char)Ch < 0x20 && Ch != '\n' && Ch != '\t'
               ? " "
               : std::string(1, Ch);
    return E;
  };
  unsigned Failures = llvm::count_if(
      Results, [](const LogResult &R) { return !R.Passed; });
  llvm::raw_ostream &OS = Out.os();
  OS << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
     << "<testsuite name=\"bsc replay\" tests=\"" << Results.size()
     << "\" failures=\"" << Failures << "\">\n";
  for (const LogResult &R : Results) {
    OS << "  <testcase classname=\"bsc.replay\" name=\"" << Escape(R.Path)
       << "\" time=\"" << llvm::format("%.3f", R.Seconds) << "\"";
    if (R.Passed) {
      OS << "/>\n";
      continue;
    }
    llvm::StringRef First = llvm::StringRef(R.Report).split('\n').first;
    OS << ">\n    <failure message=\"" << Escape(First) << "\">"
       << Escape(R.Report) << "</failure>\n  </testcase>\n";
  }
  OS << "</testsuite>\n";
  Out.keep();
  return true;
}

/// What the corpus exercised: the summary, `--coverage`'s tracefile and
/// `--fail-under`. False after reporting.
static bool reportCorpusCoverage(Compilation &C, const LoadedBehavior &L,
                                 const ReplayLogsOptions &Opts,
                                 llvm::ArrayRef<uint64_t> Counts,
                                 llvm::raw_ostream &OS) {
  CoverageSummary Summary = summarizeCoverage(C, L, Counts);
  printCoverageSummary(OS, Summary);
  OS.flush();
  bool OK = Opts.CoveragePath.empty() ||
            writeLcov(C, L, Counts, Opts.CoveragePath, "replay");
  if (Opts.CoverageFloor)
    OK &= checkCoverageFloor(C, Summary, *Opts.CoverageFloor);
  return OK;
}

llvm::Expected<int> bsc::replayLogs(Compilation &C, LoadedBehavior &L,
                                    const ReplayLogsOptions &Opts,
                                    llvm::raw_ostream &OS) {
  std::vector<std::string> Logs;
  if (!findLogs(C, Opts.LogsDir, Logs))
    return 1;
  std::vector<LogResult> Results;
  for (size_t I = Opts.Shard - 1; I < Logs.size(); I += Opts.Shards) {
    llvm::Expected<LogResult> One = replayOne(C, L, Opts, Logs[I]);
    if (!One)
      return One.takeError();
    Results.push_back(std::move(*One));
    const LogResult &R = Results.back();
    OS << (R.Passed ? "PASS " : "FAIL ") << R.Path << " (" << R.Cycles
       << (R.Cycles == 1 ? " cycle)\n" : " cycles)\n");
    if (!R.Passed)
      OS << R.Report;
    OS.flush();
  }
  unsigned Failed = llvm::count_if(
      Results, [](const LogResult &R) { return !R.Passed; });
  OS << Results.size() - Failed << " passed, " << Failed << " failed\n";
  // The sessions shared the JIT's counters: they hold the whole corpus.
  bool CoverageOK = reportCorpusCoverage(C, L, Opts, readCoverage(L), OS);
  if (!Opts.JUnitPath.empty() && !writeJUnit(C, Opts.JUnitPath, Results))
    return 1;
  return Failed || !CoverageOK ? 1 : 0;
}
