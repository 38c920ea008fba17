//===- ReplayLogs.cpp - `bsc replay`: many recorded runs, one compile -----===//
//
// The behavior is compiled once; each recording under the folder is then
// replayed in a fresh session (its own state, as a robot starts), one
// after the other. A log passes when every recorded output matches; a
// damaged or failing log fails alone, with its diagnostics, and the others
// still run. `--shard K/N` takes every N-th log from the K-th of the
// sorted list, so that N machines together replay each log once;
// `--jobs N` replays them in N worker processes (ReplayWorkers.h).
//
//===----------------------------------------------------------------------===//
#include "CycleQuestion.h"
#include "ReplayLog.h"
#include "ReplayWorkers.h"
#include "bsc/Basic/Output.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/Path.h"
#include "llvm/Support/ToolOutputFile.h"
#include "llvm/Support/raw_ostream.h"
#include <chrono>
#include <map>
#include <fcntl.h>

using namespace bsc;

/// The recordings (`.jsonl`) and binary logs (`.bslog`) under `Dir`,
/// sorted; false after reporting a folder
/// that cannot be read, has no recording, or holds a file that is not one
/// (a CI job that lost its corpus, or copied something else into it, must
/// not pass). Hidden files (`.gitkeep`) are skipped.
static bool findLogs(Compilation &C, llvm::StringRef Dir,
                     std::vector<std::string> &Logs) {
  if (!llvm::sys::fs::is_directory(Dir)) {
    C.Diags.report(llvm::SMLoc(), diag::err_replay_logs_not_folder) << Dir;
    return false;
  }
  std::error_code EC;
  std::vector<std::string> Others;
  for (llvm::sys::fs::recursive_directory_iterator It(Dir, EC), End;
       It != End && !EC; It.increment(EC)) {
    if (It->type() == llvm::sys::fs::file_type::directory_file ||
        llvm::sys::path::filename(It->path()).starts_with("."))
      continue;
    llvm::StringRef Extension = llvm::sys::path::extension(It->path());
    if (Extension == ".jsonl" || Extension == ".bslog")
      Logs.push_back(It->path());
    else
      Others.push_back(It->path());
  }
  if (EC) {
    C.Diags.report(llvm::SMLoc(), diag::err_cannot_open_file)
        << Dir << EC.message();
    return false;
  }
  llvm::sort(Others);
  for (const std::string &Other : Others)
    C.Diags.report(llvm::SMLoc(), diag::err_replay_logs_not_recording)
        << Other << Dir;
  if (Logs.empty() && Others.empty())
    C.Diags.report(llvm::SMLoc(), diag::err_replay_logs_empty) << Dir;
  llvm::sort(Logs);
  return !Logs.empty() && Others.empty();
}


/// How a log failed, the same for logs that fail alike: each diagnostic's
/// kind and message with its numbers left out (the cycle, the values), and
/// for an output that differs, the member only; the first task that went
/// astray, but not its `:why` (values).
static std::string failureGroup(llvm::ArrayRef<Diagnostic> Diags) {
  std::string Group;
  for (const Diagnostic &D : Diags) {
    if (D.Kind == diag::note_replay_why)
      continue;
    llvm::StringRef Message = D.Message;
    if (D.Kind == diag::note_replay_difference)
      Message = Message.split(": recorded").first;
    Group += std::to_string(unsigned(D.Kind)) + ":";
    for (char Ch : Message)
      if (!llvm::isDigit(Ch))
        Group += Ch;
    Group += "\n";
  }
  return Group;
}

llvm::Expected<bool> bsc::replayLog(Compilation &C, LoadedBehavior &L,
                                      const ReplayLogsOptions &Opts,
                                      const std::string &Path, RunOptions Run,
                                      uint32_t &Cycles) {
  auto T = Team::start(C, L, 1);
  if (!T)
    return T.takeError();
  if (!*T)
    return false;
  // What registered C++ prints in a regression replay is not the report.
  static int Discard = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
  (*T)->setWorldOutput(Discard);
  Run.ReplayPath = Path;
  Run.CycleLimitMs = Opts.CycleLimitMs;
  Run.RobotsFromRecording = true; // A team's log replays its team.
  Run.Regression = Opts.Regression;
  Run.Compare = Opts.Compare;
  Run.AnnounceReplayMode = false; // Counted for the summary instead.
  // --world: the robots' user pointers, as on the robot; the log's inputs
  // replace the world's begin and end hooks.
  bool Passed = (Opts.WorldLibrary.empty() ||
                 (*T)->attachWorld(C, L, Opts.WorldLibrary,
                                   Opts.CycleLimitMs)) &&
                runTeam(C, L, **T, Run, llvm::nulls()) && !C.Diags.hasErrors();
  Cycles = (**T)[0].getCycle();
  return Passed;
}

/// The second look at a log that failed as `Failure` says: replayed again
/// by the explaining behavior, which notes the first task that differed
/// from the recording and its `:why` (RunOptions::Explain). Returns those
/// notes only.
static llvm::Expected<std::vector<Diagnostic>>
explainFailedLog(Compilation &C, LoadedBehavior &Explaining,
               const ReplayLogsOptions &Opts, const std::string &Path,
               const ReplayFailure &Failure) {
  RunOptions Run;
  Run.Explain = &Failure;
  uint32_t Cycles = 0;
  llvm::Expected<bool> Passed =
      replayLog(C, Explaining, Opts, Path, Run, Cycles);
  if (!Passed)
    return Passed.takeError();
  std::vector<Diagnostic> Notes;
  for (const Diagnostic &D : C.Diags.getDiagnostics())
    if (D.Kind == diag::note_replay_first_task ||
        D.Kind == diag::note_replay_why ||
        D.Kind == diag::note_replay_tasks_as_recorded ||
        D.Kind == diag::note_replay_no_tasks ||
        D.Kind == diag::note_replay_not_explained ||
        (D.Kind == diag::note_team_robot && !Notes.empty()))
      Notes.push_back(D);
  C.Diags.clear();
  return Notes;
}

/// Replays one log in a fresh session of `L`, asking `Question` (--find)
/// after each cycle if given; an llvm::Error is internal.
static llvm::Expected<LogResult> replayOne(Compilation &C, LoadedBehavior &L,
                                           const ReplayLogsOptions &Opts,
                                           CycleQuestion *Question,
                                           const std::string &Path) {
  LogResult R;
  LogSources Sources(C.SM);
  auto Start = std::chrono::steady_clock::now();
  RunOptions Run;
  ReplayFailure Failure;
  Run.Failed = &Failure;
  if (Opts.Update) {
    // Recorded again beside the log, then over it: in the log's format
    // (its extension), under a hidden name --logs never takes for a log.
    llvm::SmallString<128> Temp = llvm::sys::path::parent_path(Path);
    llvm::sys::path::append(Temp, "." + llvm::sys::path::filename(Path) +
                                      ".update" +
                                      llvm::sys::path::extension(Path));
    Run.RecordPath = Temp.str().str();
    Run.Changed = &R.Changed;
  }
  Run.ReplayedExactly = &R.Exact;
  bool Answered = false; // --first: stopped at the first stretch found.
  if (Question) {
    Question->startLog();
    Run.TakeCycle = [&](unsigned K, BehaviorSession &S) {
      if (!Question->ask(C, K, S))
        return false;
      Answered = Opts.FindFirst && Question->justFound();
      return !Answered;
    };
  }
  llvm::Expected<bool> Passed = replayLog(C, L, Opts, Path, Run, R.Cycles);
  if (!Passed)
    return Passed.takeError();
  R.Passed = *Passed || (Answered && !C.Diags.hasErrors());
  if (Question)
    R.Found = Question->finishLog(R.Stretches);
  if (Opts.Update) {
    std::error_code EC;
    if (R.Passed && (EC = llvm::sys::fs::rename(Run.RecordPath, Path)))
      C.Diags.report(llvm::SMLoc(), diag::err_cannot_write_output)
          << Path << EC.message();
    R.Updated = R.Passed && !EC;
    R.Passed = R.Updated;
    llvm::sys::fs::remove(Run.RecordPath);
  }
  std::vector<Diagnostic> Diags = C.Diags.getDiagnostics().vec();
  C.Diags.clear();
  if (!R.Passed && Failure.Cycle && Opts.ExplainingBehavior)
    if (LoadedBehavior *Explaining = Opts.ExplainingBehavior()) {
      llvm::Expected<std::vector<Diagnostic>> Notes =
          explainFailedLog(C, *Explaining, Opts, Path, Failure);
      if (!Notes)
        return Notes.takeError();
      Diags.insert(Diags.end(), Notes->begin(), Notes->end());
    }
  R.Seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                            Start)
                  .count();
  llvm::raw_string_ostream OS(R.Report);
  printDiagnostics(C.SM, Diags, OS);
  if (!R.Passed)
    R.Group = failureGroup(Diags);
  return R;
}

/// `--junit FILE`: one test case per log, for CI systems.
static bool writeJUnit(Compilation &C, llvm::StringRef Path,
                       llvm::ArrayRef<std::string> Logs,
                       const std::vector<LogResult> &Results) {
  std::unique_ptr<llvm::ToolOutputFile> Out =
      openOutput(C.Diags, Path, /*Text=*/true);
  if (!Out)
    return false;
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
  llvm::raw_ostream &OS = Out->os();
  OS << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
     << "<testsuite name=\"bsc replay\" tests=\"" << Results.size()
     << "\" failures=\"" << Failures << "\">\n";
  for (size_t I = 0; I < Results.size(); ++I) {
    const LogResult &R = Results[I];
    OS << "  <testcase classname=\"bsc.replay\" name=\"" << Escape(Logs[I])
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
  Out->keep();
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

namespace {
/// Failures that happened alike (failureGroup): the first is reported in
/// full, the others by a line that names it, and the end lists each
/// group's logs.
class FailureGroups {
public:
  /// `Asking`: --find's stretches follow each log's line.
  explicit FailureGroups(bool Asking) : Asking(Asking) {}
  /// The log's line, --find's stretches and, if it failed, its
  /// diagnostics (or the first log that failed alike).
  void print(llvm::raw_ostream &OS, llvm::StringRef Path, const LogResult &R) {
    OS << (R.Updated ? "UPDATED " : R.Passed ? "PASS " : "FAIL ") << Path
       << " (" << R.Cycles
       << (R.Cycles == 1 ? " cycle)" : " cycles)");
    llvm::StringRef Report = R.Passed ? "" : llvm::StringRef(R.Report);
    if (!R.Passed && !R.Group.empty()) {
      auto [It, New] = Groups.try_emplace(R.Group, Order.size());
      if (New) {
        Order.push_back({Path.str(), {}});
      } else {
        Order[It->second].Others.push_back(Path.str());
        OS << ": fails as " << Order[It->second].First << " does";
        Report = "";
      }
    }
    OS << "\n";
    if (Asking)
      OS << (R.Stretches ? llvm::StringRef(R.Found) : "  not found\n");
    OS << Report;
    OS.flush();
  }
  /// `a.jsonl and 6 more logs failed alike: ...` for each group of more
  /// than one.
  void summarize(llvm::raw_ostream &OS) const {
    for (const Group &G : Order) {
      if (G.Others.empty())
        continue;
      OS << G.First << " and " << G.Others.size()
         << (G.Others.size() == 1 ? " more log" : " more logs")
         << " failed alike: ";
      for (size_t I = 0; I < G.Others.size() && I < 10; ++I)
        OS << (I ? ", " : "") << llvm::sys::path::filename(G.Others[I]);
      if (G.Others.size() > 10)
        OS << ", ...";
      OS << "\n";
    }
  }

private:
  struct Group {
    std::string First;
    std::vector<std::string> Others;
  };
  bool Asking;
  llvm::StringMap<size_t> Groups;
  std::vector<Group> Order;
};
} // namespace

/// --update's summary: what changed, per output member.
static void summarizeUpdate(llvm::raw_ostream &OS,
                            llvm::ArrayRef<LogResult> Results) {
  std::map<std::string, std::pair<unsigned, unsigned>> Members; // Cycles, logs.
  unsigned Updated = 0;
  for (const LogResult &R : Results) {
    Updated += R.Updated;
    for (const auto &[Member, Cycles] : R.Changed) {
      Members[Member].first += Cycles;
      ++Members[Member].second;
    }
  }
  OS << Updated << (Updated == 1 ? " log" : " logs")
     << " recorded again with this behavior's outputs on their own inputs "
        "(open loop: the inputs are as recorded, not as a world would "
        "answer the new outputs)\n";
  OS << "changed:";
  if (Members.empty())
    OS << " nothing";
  bool First = true;
  for (const auto &[Member, CyclesLogs] : Members) {
    OS << (First ? " " : ", ") << Member << " in " << CyclesLogs.first
       << (CyclesLogs.first == 1 ? " cycle" : " cycles") << " of "
       << CyclesLogs.second << (CyclesLogs.second == 1 ? " log" : " logs");
    First = false;
  }
  OS << "\n";
}

/// `--jobs N`: the logs in N worker processes; a worker that dies fails
/// the log it was on with a diagnostic saying how it died.
static llvm::Expected<std::vector<LogResult>>
replayForked(Compilation &C, LoadedBehavior &L, const ReplayLogsOptions &Opts,
             CycleQuestion *Question, llvm::ArrayRef<std::string> Logs,
             llvm::raw_ostream &OS, FailureGroups &Failures) {
  auto Died = [&](llvm::StringRef Fate) {
    LogResult R;
    C.Diags.report(llvm::SMLoc(), diag::err_replay_worker_died) << Fate;
    llvm::raw_string_ostream RS(R.Report);
    printDiagnostics(C.SM, C.Diags.getDiagnostics(), RS);
    C.Diags.clear();
    return R;
  };
  // A worker's JIT counters are its own copy: each log sends what it
  // added, and the parent sums them.
  auto ReplayOne = [&](size_t I) {
    llvm::Expected<LogResult> R = replayOne(C, L, Opts, Question, Logs[I]);
    if (R) {
      R->Coverage = readCoverage(L);
      clearCoverage(L);
    }
    return R;
  };
  return replayInWorkers(
      Logs.size(), Opts.Jobs, ReplayOne, Died,
      [&](size_t I, const LogResult &R) { Failures.print(OS, Logs[I], R); });
}

llvm::Expected<int> bsc::replayLogs(Compilation &C, LoadedBehavior &L,
                                    const ReplayLogsOptions &Opts,
                                    llvm::raw_ostream &OS) {
  std::vector<std::string> All, Logs;
  if (!findLogs(C, Opts.LogsDir, All))
    return 1;
  for (size_t I = Opts.Shard - 1; I < All.size(); I += Opts.Shards)
    Logs.push_back(All[I]);
  // --find's question, compiled before the workers fork.
  std::unique_ptr<CycleQuestion> Question;
  if (!Opts.Find.empty() &&
      !(Question = CycleQuestion::compile(C, L, Opts.Find, Opts.FindLasting)))
    return 1;
  std::vector<LogResult> Results;
  FailureGroups Failures(Question != nullptr);
  if (Opts.Jobs > 1) {
    auto Forked =
        replayForked(C, L, Opts, Question.get(), Logs, OS, Failures);
    if (!Forked)
      return Forked.takeError();
    Results = std::move(*Forked);
  } else {
    // In this process, so that a debugger sees the replay.
    for (const std::string &Path : Logs) {
      llvm::Expected<LogResult> One =
          replayOne(C, L, Opts, Question.get(), Path);
      if (!One)
        return One.takeError();
      Results.push_back(std::move(*One));
      Failures.print(OS, Path, Results.back());
    }
  }
  unsigned Failed = llvm::count_if(
      Results, [](const LogResult &R) { return !R.Passed; });
  Failures.summarize(OS);
  if (Opts.Update)
    summarizeUpdate(OS, Results);
  if (Question) {
    unsigned Logs = 0, Stretches = 0;
    for (const LogResult &R : Results) {
      Logs += R.Stretches > 0;
      Stretches += R.Stretches;
    }
    OS << "'" << Question->getText() << "' held in " << Logs << " of "
       << Results.size() << (Results.size() == 1 ? " log" : " logs") << ", "
       << Stretches << (Stretches == 1 ? " time" : " times");
    if (Opts.FindLasting > 1)
      OS << " for " << Opts.FindLasting << " cycles or more";
    if (Opts.FindFirst)
      OS << " (--first: each log up to its first)";
    OS << "\n";
  }
  unsigned Exact = llvm::count_if(
      Results, [](const LogResult &R) { return R.Exact; });
  if (!Results.empty())
    OS << Exact << " of " << Results.size()
       << " logs replayed exactly (calls into C++ from the log), "
       << Results.size() - Exact
       << " in regression mode (C++ called for real)\n";
  OS << Results.size() - Failed << " passed, " << Failed << " failed\n";
  OS.flush();
  // In this process the sessions shared the JIT's counters, which then
  // hold the whole corpus; workers sent each log's own.
  std::vector<uint64_t> Counts = readCoverage(L);
  for (const LogResult &R : Results)
    for (size_t I = 0; I < R.Coverage.size() && I < Counts.size(); ++I)
      Counts[I] += R.Coverage[I];
  bool CoverageOK = reportCorpusCoverage(C, L, Opts, Counts, OS);
  if (!Opts.JUnitPath.empty() &&
      !writeJUnit(C, Opts.JUnitPath, Logs, Results))
    return 1;
  return Failed || !CoverageOK ? 1 : 0;
}
