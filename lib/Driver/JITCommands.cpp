//===- JITCommands.cpp - `bsc run`, `replay`, `repl`: the host JIT ------===//
//
// Each checks its options, then hands over: `bsc run` and `bsc replay`
// (lib/Run) load the behavior, start a session and run its cycles (with a
// --world library feeding it, or a recording); `bsc repl` (lib/REPL) lets
// the REPL load and reload the files itself. All run on the host whatever
// -target says (the tool gives them the host's ToolChain). (Named apart
// from lib/Run, whose Run.h is the runner's.)
//
//===----------------------------------------------------------------------===//
#include "bsc/Driver/Driver.h"
#include "bsc/Run/Run.h"
#include "bsc/REPL/Repl.h"
#include "llvm/Support/Path.h"
#include "llvm/Support/Threading.h"
#include "llvm/Support/raw_ostream.h"
#include <algorithm>

using namespace bsc;

/// `--world-output` redirects what the world library and registered C++
/// print: without either it is a mistake.
static bool checkWorldOutputOption(Compilation &C, llvm::StringRef WorldLibrary,
                                   llvm::StringRef WorldOutput,
                                   bool HasBindings) {
  if (WorldOutput.empty() || !WorldLibrary.empty() || HasBindings)
    return true;
  C.Diags.report(llvm::SMLoc(), diag::err_option_needs_option)
      << "--world-output" << "--world' or '--bind";
  return false;
}

/// `--fail-under PERCENT` (0 to 100); false after reporting.
static bool parseCoverageFloor(DiagnosticEngine &Diags, llvm::StringRef Arg,
                               std::optional<double> &Floor) {
  if (Arg.empty())
    return true;
  double V;
  if (Arg.getAsDouble(V) || !(V >= 0 && V <= 100)) {
    Diags.report(llvm::SMLoc(), diag::err_bad_option_value)
        << Arg << "--fail-under";
    return false;
  }
  Floor = V;
  return true;
}

/// `--ignore MEMBER` and `--tolerance MEMBER=ABS` (ABS a number >= 0);
/// false after reporting.
static bool parseComparison(DiagnosticEngine &Diags, const CompareArgs &Args,
                            OutputComparison &Into) {
  bool OK = true;
  for (const std::string &Member : Args.Ignore) {
    if (Member.empty()) {
      Diags.report(llvm::SMLoc(), diag::err_bad_option_value)
          << Member << "--ignore";
      OK = false;
    }
    Into.Ignore.push_back(Member);
  }
  for (const std::string &Arg : Args.Tolerance) {
    auto [Member, Text] = llvm::StringRef(Arg).split('=');
    double Abs;
    if (Member.empty() || Text.empty() || Text.getAsDouble(Abs) ||
        !(Abs >= 0)) {
      Diags.report(llvm::SMLoc(), diag::err_bad_option_value)
          << Arg << "--tolerance";
      OK = false;
      continue;
    }
    Into.Tolerance.push_back({Member.str(), Abs});
  }
  return OK;
}

/// `bsc run --coverage/--fail-under` after the run: the tracefile and the
/// floor. False after reporting.
static bool finishRunCoverage(Compilation &C, const LoadedBehavior &L,
                              const CoverageArgs &Args,
                              std::optional<double> Floor) {
  std::vector<uint64_t> Counts = readCoverage(L);
  bool OK = Args.Path.empty() ||
            writeLcov(C, L, Counts, Args.Path, L.Entry->getQualifiedName());
  if (Floor)
    OK &= checkCoverageFloor(C, summarizeCoverage(C, L, Counts), *Floor);
  return OK;
}

/// Loads the checked behavior into the JIT and runs its cycles.
static int loadAndRun(Compilation &C, const RunCommandOptions &Opts,
                      const LoadOptions &LOpts, const RunOptions &ROpts,
                      unsigned RobotCount, const CallableDecl &Entry,
                      std::optional<double> CoverageFloor) {
  auto Loaded = loadBehavior(C, Entry, LOpts);
  if (!Loaded)
    return finishWithInternalError(C, Loaded.takeError());
  if (!*Loaded)
    return finishCompilation(C);
  if (!checkWorldOutputOption(C, Opts.WorldLibrary, Opts.WorldOutput,
                              !LOpts.BindObjects.empty()))
    return finishCompilation(C);
  int WorldOutputFd = -1;
  if (!Opts.WorldOutput.empty() &&
      (WorldOutputFd = openWorldOutput(C, Opts.WorldOutput)) < 0)
    return finishCompilation(C);
  auto Robots = Team::start(C, **Loaded, RobotCount);
  if (!Robots)
    return finishWithInternalError(C, Robots.takeError());
  if (*Robots)
    (*Robots)->setWorldOutput(WorldOutputFd);
  if (*Robots && (Opts.WorldLibrary.empty() ||
                  (*Robots)->attachWorld(C, **Loaded, Opts.WorldLibrary,
                                         ROpts.CycleLimitMs)))
    runTeam(C, **Loaded, **Robots, ROpts, llvm::outs());
  // What ran until the end or the error, so a failing run still tells
  // (every robot's cycles: the robots share the JIT's counters).
  if (LOpts.Coverage)
    finishRunCoverage(C, **Loaded, Opts.Coverage, CoverageFloor);
  return finishCompilation(C);
}

/// The front end for `run` and `replay` (also after bad options, whose
/// errors are then reported with the files'), then their entry and how to
/// load it into the JIT; null after reporting.
static const CallableDecl *checkForJIT(Compilation &C,
                                       const FrontendOptions &FOpts,
                                       bool OptionsOK, llvm::StringRef EntryName,
                                       const BackendOptions &BOpts,
                                       bool DebugInfo, LoadOptions &LOpts) {
  if (!runFrontend(C, FOpts) || !OptionsOK)
    return nullptr;
  const CallableDecl *Entry = findProgramEntry(C, EntryName);
  LOpts.OptLevel = BOpts.Target.OptLevel;
  LOpts.StandardModules = FOpts.StandardModules;
  LOpts.BindObjects = FOpts.BindObjects;
  LOpts.DebugInfo = DebugInfo;
  return Entry;
}

int bsc::runCommand(Compilation &C, const FrontendOptions &FOpts,
                    const RunCommandOptions &Opts) {
  BackendOptions BOpts;
  bool OptionsOK = parseBackendOptions(C.Diags, Opts.Backend, BOpts);
  RunOptions ROpts;
  ROpts.Cycles = BOpts.Cycles;
  ROpts.CyclesGiven = Opts.CyclesGiven;
  ROpts.RecordPath = Opts.RecordPath;
  ROpts.ReplayPath = Opts.ReplayPath;
  ROpts.PrintOutput = Opts.PrintOutput;
  ROpts.Regression = Opts.Regression;
  OptionsOK &= parseComparison(C.Diags, Opts.Compare, ROpts.Compare);
  if (!ROpts.Compare.isExact() && Opts.ReplayPath.empty()) {
    C.Diags.report(llvm::SMLoc(), diag::err_option_needs_option)
        << (Opts.Compare.Ignore.empty() ? "--tolerance" : "--ignore")
        << "--replay";
    OptionsOK = false;
  }
  unsigned Robots;
  OptionsOK &= parseRobots(C.Diags, Opts.Robots, Robots);
  // Without --robots a replay runs the recording's team.
  ROpts.RobotsFromRecording = !Opts.Robots;
  OptionsOK &= parseTraceMode(C.Diags, Opts.Trace, ROpts.Trace,
                              ROpts.TraceTask);
  OptionsOK &= parseCycleLimit(C.Diags, Opts.CycleLimit, ROpts.CycleLimitMs);
  uint32_t CycleBudget = 0;
  OptionsOK &= parseCycleBudget(C.Diags, Opts.CycleBudget, CycleBudget);
  std::optional<double> CoverageFloor;
  OptionsOK &= parseCoverageFloor(C.Diags, Opts.Coverage.Floor, CoverageFloor);
  LoadOptions LOpts;
  const CallableDecl *Entry = checkForJIT(C, FOpts, OptionsOK, Opts.EntryName,
                                          BOpts, Opts.DebugInfo, LOpts);
  if (!Entry)
    return finishCompilation(C);
  LOpts.CycleBudget = CycleBudget;
  LOpts.Coverage = !Opts.Coverage.Path.empty() || CoverageFloor;
  return loadAndRun(C, Opts, LOpts, ROpts, Robots, *Entry, CoverageFloor);
}

/// The behavior of `--behavior FILES` (with `--entry`, `--bind`, `-I`) in
/// the host JIT, for the commands that read binary logs with its layout.
/// Null after reporting; `Status` is then the exit status.
static std::unique_ptr<LoadedBehavior>
loadBehaviorFiles(Compilation &C, const FrontendOptions &FOpts,
                  const std::vector<std::string> &Files,
                  llvm::StringRef EntryName, int &Status) {
  FrontendOptions Behavior = FOpts;
  Behavior.Inputs = Files;
  LoadOptions LOpts;
  const CallableDecl *Entry =
      checkForJIT(C, Behavior, /*OptionsOK=*/true, EntryName,
                  BackendOptions(), /*DebugInfo=*/false, LOpts);
  if (!Entry) {
    Status = finishCompilation(C);
    return nullptr;
  }
  auto Loaded = loadBehavior(C, *Entry, LOpts);
  if (!Loaded) {
    Status = finishWithInternalError(C, Loaded.takeError());
    return nullptr;
  }
  if (!*Loaded)
    Status = finishCompilation(C);
  return std::move(*Loaded);
}

int bsc::timelineCommand(Compilation &C, const FrontendOptions &FOpts,
                         timeline::TimelineOptions Opts) {
  if (Opts.BehaviorFiles.empty()) {
    timeline::writeTimeline(C, Opts, llvm::outs());
    return finishCompilation(C);
  }
  int Status = 1;
  std::unique_ptr<LoadedBehavior> Loaded =
      loadBehaviorFiles(C, FOpts, Opts.BehaviorFiles, Opts.EntryName, Status);
  if (!Loaded)
    return Status;
  LoadedBehavior &L = *Loaded;
  // Each log is replayed by robots of its own, from their first cycle.
  llvm::Error Internal = llvm::Error::success();
  Opts.ReplayLog = [&](llvm::StringRef Path,
                       const timeline::TimelineOptions::SinkForRobot &SinkFor) {
    auto Robots = Team::start(C, L, 1);
    if (!Robots) {
      Internal = Robots.takeError();
      return false;
    }
    if (!*Robots)
      return false;
    // A feed per robot: each keeps its robot's cycle before. The replay
    // grew the team to the log's robots before the first cycle.
    std::vector<std::unique_ptr<TimelineFeed>> Feeds;
    RunOptions ROpts;
    ROpts.ReplayPath = Path.str();
    ROpts.RobotsFromRecording = true;
    ROpts.CycleLimitMs = DefaultCycleLimitMs;
    ROpts.TakeCycle = [&](unsigned Robot, BehaviorSession &S) {
      while (Feeds.size() <= Robot)
        Feeds.push_back(std::make_unique<TimelineFeed>(
            L, SinkFor(Feeds.size(), (*Robots)->size())));
      Feeds[Robot]->take(S);
      return true;
    };
    return runTeam(C, L, **Robots, ROpts, llvm::nulls()) &&
           !C.Diags.hasErrors();
  };
  timeline::writeTimeline(C, Opts, llvm::outs());
  if (Internal)
    return finishWithInternalError(C, std::move(Internal));
  return finishCompilation(C);
}

int bsc::convertCommand(Compilation &C, const FrontendOptions &FOpts,
                        const ConvertCommandOptions &Opts) {
  for (const auto &[Given, Option] :
       {std::pair(&Opts.From, "a recording or log to convert"),
        std::pair(&Opts.To, "-o FILE")})
    if (Given->empty()) {
      C.Diags.report(llvm::SMLoc(), diag::err_convert_needs) << Option;
      return finishCompilation(C);
    }
  if (Opts.BehaviorFiles.empty()) {
    C.Diags.report(llvm::SMLoc(), diag::err_convert_needs)
        << "--behavior FILE.bs (the layout of input and output)";
    return finishCompilation(C);
  }
  int Status = 1;
  std::unique_ptr<LoadedBehavior> Loaded =
      loadBehaviorFiles(C, FOpts, Opts.BehaviorFiles, Opts.EntryName, Status);
  if (!Loaded)
    return Status;
  auto S = startSession(C, *Loaded);
  if (!S)
    return finishWithInternalError(C, S.takeError());
  if (*S)
    convertRecording(C, *Loaded, **S, Opts.From, Opts.To);
  return finishCompilation(C);
}

/// `--shard K/N` into K and N; false after reporting.
static bool parseShard(DiagnosticEngine &Diags, llvm::StringRef Arg,
                       unsigned &K, unsigned &N) {
  if (Arg.empty())
    return true;
  auto [KText, NText] = Arg.split('/');
  if (KText.getAsInteger(10, K) || NText.getAsInteger(10, N) || K < 1 ||
      K > N) {
    Diags.report(llvm::SMLoc(), diag::err_bad_shard) << Arg;
    return false;
  }
  return true;
}

/// `--jobs N` (N >= 1); without it, one worker per core this process may
/// run on (its affinity: a cluster's job gets the cores it was given).
static bool parseJobs(DiagnosticEngine &Diags, llvm::StringRef Arg,
                      unsigned &Jobs) {
  if (Arg.empty()) {
    Jobs = std::max(1u, llvm::hardware_concurrency().compute_thread_count());
    return true;
  }
  if (Arg.getAsInteger(10, Jobs) || Jobs < 1 || Jobs > MaxReplayJobs) {
    Diags.report(llvm::SMLoc(), diag::err_bad_option_value) << Arg << "--jobs";
    return false;
  }
  return true;
}

int bsc::replayCommand(Compilation &C, const FrontendOptions &FOpts,
                       const ReplayCommandOptions &Opts) {
  BackendOptions BOpts;
  bool OK = parseBackendOptions(C.Diags, Opts.Backend, BOpts);
  ReplayLogsOptions ROpts;
  ROpts.LogsDir = Opts.LogsDir;
  ROpts.JUnitPath = Opts.JUnitPath;
  OK &= parseShard(C.Diags, Opts.Shard, ROpts.Shard, ROpts.Shards);
  OK &= parseJobs(C.Diags, Opts.Jobs, ROpts.Jobs);
  OK &= parseCycleLimit(C.Diags, Opts.CycleLimit, ROpts.CycleLimitMs);
  ROpts.CoveragePath = Opts.Coverage.Path;
  OK &= parseCoverageFloor(C.Diags, Opts.Coverage.Floor, ROpts.CoverageFloor);
  ROpts.WorldLibrary = Opts.WorldLibrary;
  ROpts.Regression = Opts.Regression;
  OK &= parseComparison(C.Diags, Opts.Compare, ROpts.Compare);
  ROpts.Update = Opts.Update;
  ROpts.Find = Opts.Find.value_or("");
  if (Opts.Find && llvm::StringRef(*Opts.Find).trim().empty()) {
    C.Diags.report(llvm::SMLoc(), diag::err_replay_find_not_bool)
        << *Opts.Find << "empty";
    OK = false;
  }
  ROpts.FindFirst = Opts.FindFirst;
  for (const auto &[Given, Name] :
       {std::pair(Opts.FindFirst, "--first"),
        std::pair(!Opts.Lasting.empty(), "--lasting")})
    if (Given && !Opts.Find) {
      C.Diags.report(llvm::SMLoc(), diag::err_option_needs_option)
          << Name << "--find";
      OK = false;
    }
  if (!Opts.Lasting.empty() &&
      (llvm::StringRef(Opts.Lasting).getAsInteger(10, ROpts.FindLasting) ||
       ROpts.FindLasting < 1)) {
    C.Diags.report(llvm::SMLoc(), diag::err_bad_option_value)
        << Opts.Lasting << "--lasting";
    OK = false;
  }
  if (Opts.Find && Opts.Update) {
    C.Diags.report(llvm::SMLoc(), diag::err_conflicting_options)
        << "--find" << "--update";
    OK = false;
  }
  // --shrink takes one log instead of a folder.
  if (!Opts.Shrink.empty()) {
    for (const auto &[Given, Name] :
         {std::pair(!Opts.LogsDir.empty(), "--logs"),
          std::pair(Opts.Find.has_value(), "--find"),
          std::pair(Opts.Update, "--update")})
      if (Given) {
        C.Diags.report(llvm::SMLoc(), diag::err_conflicting_options)
            << "--shrink" << Name;
        OK = false;
      }
  } else if (!Opts.ShrinkOutput.empty()) {
    C.Diags.report(llvm::SMLoc(), diag::err_option_needs_option)
        << "-o" << "--shrink";
    OK = false;
  } else if (Opts.LogsDir.empty()) {
    C.Diags.report(llvm::SMLoc(), diag::err_option_needs_option)
        << "replay" << "--logs";
    OK = false;
  }
  LoadOptions LOpts;
  const CallableDecl *Entry = checkForJIT(C, FOpts, OK, Opts.EntryName, BOpts,
                                          Opts.DebugInfo, LOpts);
  if (!Entry)
    return finishCompilation(C);
  LOpts.Coverage = true; // The corpus's summary.
  auto Loaded = loadBehavior(C, *Entry, LOpts);
  if (!Loaded)
    return finishWithInternalError(C, Loaded.takeError());
  if (!*Loaded)
    return finishCompilation(C);
  // The compile's warnings once, before the logs' own diagnostics.
  printDiagnostics(C.SM, C.Diags.getDiagnostics(), llvm::errs());
  C.Diags.clear();
  // A failure's report replays the log again with the conditions recorded,
  // which slows every cycle: that build is made for the first failure
  // only (in each worker).
  std::unique_ptr<LoadedBehavior> Explaining;
  bool TriedExplaining = false;
  if (!ROpts.Update)
    ROpts.ExplainingBehavior = [&]() -> LoadedBehavior * {
      if (!TriedExplaining) {
        TriedExplaining = true;
        LoadOptions XOpts = LOpts;
        XOpts.Explain = true;
        XOpts.Coverage = false;
        auto X = loadBehavior(C, *Entry, XOpts);
        if (X)
          Explaining = std::move(*X);
        else
          llvm::consumeError(X.takeError()); // The report goes without.
      }
      return Explaining.get();
    };
  if (!Opts.Shrink.empty()) {
    std::string Out = Opts.ShrinkOutput;
    if (Out.empty()) {
      llvm::SmallString<128> Path(Opts.Shrink);
      llvm::sys::path::replace_extension(Path, "shrunk.jsonl");
      Out = Path.str().str();
    }
    llvm::Expected<int> Status =
        shrinkLog(C, **Loaded, ROpts, Opts.Shrink, Out, llvm::outs());
    if (!Status)
      return finishWithInternalError(C, Status.takeError());
    finishCompilation(C);
    return *Status;
  }
  llvm::Expected<int> Status = replayLogs(C, **Loaded, ROpts, llvm::outs());
  if (!Status)
    return finishWithInternalError(C, Status.takeError());
  int Finished = finishCompilation(C);
  return Finished ? Finished : *Status;
}

int bsc::replCommand(Compilation &C, const FrontendOptions &FOpts,
                     const ReplCommandOptions &Opts) {
  BackendOptions BOpts;
  bool OK = parseBackendOptions(C.Diags, Opts.Backend, BOpts);
  ReplOptions ROpts;
  OK &= parseCycleLimit(C.Diags, Opts.CycleLimit, ROpts.CycleLimitMs);
  if (FOpts.Inputs.empty()) {
    C.Diags.report(llvm::SMLoc(), diag::err_no_input_files);
    OK = false;
  }
  OK &= checkWorldOutputOption(C, Opts.WorldLibrary, Opts.WorldOutput,
                               !FOpts.BindObjects.empty());
  OK &= parseRobots(C.Diags, Opts.Robots, ROpts.Robots);
  OK &= parseCycleBudget(C.Diags, Opts.CycleBudget, ROpts.Load.CycleBudget);
  if (!OK)
    return finishCompilation(C);
  ROpts.Frontend = FOpts;
  ROpts.Load.OptLevel = BOpts.Target.OptLevel;
  ROpts.Load.StandardModules = FOpts.StandardModules;
  ROpts.Load.BindObjects = FOpts.BindObjects;
  ROpts.Load.DebugInfo = Opts.DebugInfo;
  ROpts.EntryName = Opts.EntryName;
  ROpts.BatchFile = Opts.BatchFile;
  ROpts.WorldLibrary = Opts.WorldLibrary;
  ROpts.WorldOutput = Opts.WorldOutput;
  return runRepl(ROpts, llvm::outs());
}
