//===- RunTest.cpp - loading a behavior, running its cycles ---------------===//
#include "bsc/Run/Run.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/Path.h"
#include "llvm/Support/raw_ostream.h"
#include "gtest/gtest.h"

using namespace bsc;

namespace {

/// A file removed at the end of the test.
class TempFile {
public:
  TempFile(llvm::StringRef Name, llvm::StringRef Text) {
    llvm::sys::fs::createUniqueDirectory("bsc-run", Dir);
    Path = (Dir + "/" + Name).str();
    std::error_code EC;
    llvm::raw_fd_ostream OS(Path, EC);
    OS << Text;
  }
  ~TempFile() { llvm::sys::fs::remove_directories(Dir); }
  std::string Path;
  llvm::SmallString<128> Dir;
};

/// A checked behavior loaded into a fresh JIT with a session started.
class RunTest : public ::testing::Test {
protected:
  /// Checks and loads `Text` (its entry `Entry`); false after an error.
  bool load(llvm::StringRef Text, llvm::StringRef Entry) {
    Script = std::make_unique<TempFile>("Behavior.bs", Text);
    FrontendOptions FOpts;
    FOpts.Inputs = {Script->Path};
    FOpts.StandardModules = {BSC_HOST_RUNTIME};
    if (!runFrontend(C, FOpts))
      return false;
    const CallableDecl *E = findProgramEntry(C, Entry);
    if (!E)
      return false;
    LoadOptions LOpts;
    LOpts.StandardModules = FOpts.StandardModules;
    LOpts.Coverage = Coverage;
    auto L = loadBehavior(C, *E, LOpts);
    EXPECT_TRUE(bool(L)) << llvm::toString(L.takeError());
    if (!L || !*L)
      return false;
    Loaded = std::move(*L);
    auto S = startSession(C, *Loaded);
    EXPECT_TRUE(bool(S)) << llvm::toString(S.takeError());
    if (!S || !*S)
      return false;
    Session = std::move(*S);
    return true;
  }

  /// Runs with `Opts`; the text written, or the errors reported.
  std::string run(const RunOptions &Opts) {
    std::string Out;
    llvm::raw_string_ostream OS(Out);
    if (!runBehavior(C, *Loaded, *Session, Opts, OS))
      return "failed: " + messages();
    return Out;
  }

  std::string messages() const {
    std::string All;
    for (const Diagnostic &D : C.Diags.getDiagnostics())
      All += D.Message + "\n";
    return All;
  }

  bool Coverage = false; ///< Load with LoadOptions::Coverage.
  Compilation C;
  std::unique_ptr<TempFile> Script;
  std::unique_ptr<LoadedBehavior> Loaded;
  std::unique_ptr<BehaviorSession> Session;
};

constexpr const char *Stepper = "task step()\n"
                                "    yield\n"
                                "    yield\n";

TEST_F(RunTest, TracesEachCycleWhereTheTaskWaits) {
  ASSERT_TRUE(load(Stepper, "step")) << messages();
  RunOptions Opts;
  Opts.Cycles = 3;
  Opts.Trace = debug::TraceMode::EveryCycle;
  EXPECT_EQ(run(Opts), "cycle 1: step [running, Behavior.bs:2]\n"
                       "cycle 2: step [running, Behavior.bs:3]\n"
                       "cycle 3: step [done]\n");
}

TEST_F(RunTest, ChangesPrintsOnlyCyclesThatDiffer) {
  ASSERT_TRUE(load("task wait()\n    for(;;)\n        yield\n", "wait"))
      << messages();
  RunOptions Opts;
  Opts.Cycles = 4;
  Opts.Trace = debug::TraceMode::Changes;
  EXPECT_EQ(run(Opts), "cycle 1: wait [running, Behavior.bs:3]\n");
}

TEST_F(RunTest, CyclesAndReplayConflict) {
  ASSERT_TRUE(load(Stepper, "step")) << messages();
  TempFile Replay("replay.jsonl", "{\"cycle\":1}\n");
  RunOptions Opts;
  Opts.CyclesGiven = true;
  Opts.ReplayPath = Replay.Path;
  EXPECT_EQ(run(Opts), "failed: '--cycles' cannot be combined with "
                       "'--replay'\n");
}

TEST_F(RunTest, AReplayOfInputsNeedsAWorld) {
  ASSERT_TRUE(load(Stepper, "step")) << messages();
  TempFile Replay("replay.jsonl", "{\"cycle\":1,\"input\":{}}\n"
                                  "{\"cycle\":2,\"speed\":3}\n\n");
  RunOptions Opts;
  Opts.ReplayPath = Replay.Path;
  Opts.Trace = debug::TraceMode::EveryCycle;
  std::string Got = run(Opts);
  EXPECT_NE(Got.find("'input'"), std::string::npos) << Got;
  // The replay stops at its first bad line: no cycle ran, line 2 is unread.
  EXPECT_EQ(Got.find("cycle 1"), std::string::npos) << Got;
  EXPECT_EQ(Got.find("'speed'"), std::string::npos) << Got;
}

TEST_F(RunTest, AReplayStopsAtItsFirstBadLine) {
  ASSERT_TRUE(load(Stepper, "step")) << messages();
  TempFile Replay("replay.jsonl", "{\"cycle\":1}\n"
                                  "{\"cycle\":2,\"speed\":3}\n"
                                  "{\"cycle\":3}\n");
  RunOptions Opts;
  Opts.ReplayPath = Replay.Path;
  Opts.Trace = debug::TraceMode::EveryCycle;
  // A recording without a header (format 1) replays in regression mode,
  // and says so first.
  EXPECT_EQ(run(Opts), "failed: replaying '" + Replay.Path +
                           "' in regression mode (the recording is of format "
                           "1, without its calls into C++): its inputs feed "
                           "the behavior and registered C++ is called for "
                           "real\nunknown key 'speed' in a replay line; "
                           "expected 'cycle', 'robot', 'input', 'output', "
                           "'tasks' or 'calls'\n");
  EXPECT_EQ(Session->getCycle(), 1u);
}

TEST_F(RunTest, AnEmptyReplayIsAnError) {
  ASSERT_TRUE(load(Stepper, "step")) << messages();
  TempFile Replay("replay.jsonl", "\n  \n");
  RunOptions Opts;
  Opts.ReplayPath = Replay.Path;
  std::string Got = run(Opts);
  EXPECT_NE(Got.find("has no cycles to replay"), std::string::npos) << Got;
}

TEST_F(RunTest, ARecordingHasALinePerCycleWithItsTasks) {
  ASSERT_TRUE(load(Stepper, "step")) << messages();
  TempFile Out("out.jsonl", "");
  RunOptions Opts;
  Opts.Cycles = 2;
  Opts.RecordPath = Out.Path;
  EXPECT_EQ(run(Opts), "");
  auto Buf = llvm::MemoryBuffer::getFile(Out.Path);
  ASSERT_TRUE(bool(Buf));
  EXPECT_EQ((*Buf)->getBuffer().str(),
            "{\"recording\":{\"behavior\":\"" + Loaded->Hash +
                "\",\"entry\":\"Behavior::step\",\"format\":2}}\n"
            "{\"cycle\":1,\"tasks\":[{\"at\":\"Behavior.bs:2\",\"parent\":-1,"
            "\"state\":\"running\",\"task\":\"Behavior::step\"}]}\n"
            "{\"cycle\":2,\"tasks\":[{\"at\":\"Behavior.bs:3\",\"parent\":-1,"
            "\"state\":\"running\",\"task\":\"Behavior::step\"}]}\n");
}

TEST_F(RunTest, ARunawayLoopIsReportedAtTheLoop) {
  ASSERT_TRUE(load("task spin()\n    int n = 0\n    for(;;)\n"
                   "        n += 1\n",
                   "spin"))
      << messages();
  RunOptions Opts;
  Opts.CycleLimitMs = 50;
  std::string Got = run(Opts);
  EXPECT_EQ(Got.rfind("failed: ", 0), 0u) << Got;
  EXPECT_NE(Got.find("cycle 1"), std::string::npos) << Got;
  ASSERT_FALSE(C.Diags.getDiagnostics().empty());
  auto [Line, Col] =
      C.SM.getLineAndColumn(C.Diags.getDiagnostics().back().Loc);
  EXPECT_EQ(Line, 3u);
}

TEST_F(RunTest, StopAfterCycleEndsTheRun) {
  ASSERT_TRUE(load(Stepper, "step")) << messages();
  RunOptions Opts;
  Opts.Cycles = 3;
  Opts.Trace = debug::TraceMode::EveryCycle;
  Opts.StopAfterCycle = [] { return true; };
  EXPECT_EQ(run(Opts), "cycle 1: step [running, Behavior.bs:2]\n");
}

TEST_F(RunTest, AMissingReplayFileIsReported) {
  ASSERT_TRUE(load(Stepper, "step")) << messages();
  RunOptions Opts;
  Opts.ReplayPath = "/nonexistent/replay.jsonl";
  EXPECT_NE(run(Opts).find("cannot open"), std::string::npos);
}

constexpr const char *Counter = "task count()\n"
                                "    int n = 0\n"
                                "    for(; true; yield)\n"
                                "        n += 1\n"
                                "        assert(n < 3 && n > 0, \"small\")\n"
                                "\n"
                                "task idle()\n"
                                "    yield\n"
                                "\n"
                                "task main()\n"
                                "    count()\n"
                                "    if(taskState(count) == TaskState::failure)\n"
                                "        idle()\n";

TEST_F(RunTest, AFailedAssertionStopsItsCycleWithTheValues) {
  ASSERT_TRUE(load(Counter, "main")) << messages();
  RunOptions Opts;
  Opts.Cycles = 5;
  std::string Got = run(Opts);
  // Cycles 1 and 2 pass; n = 3 fails in cycle 3, and the run stops there.
  EXPECT_EQ(Got, "failed: cycle 3: assertion failed: n < 3 && n > 0: small\n"
                 "n < 3 = false\n"
                 "  n = 3\n"
                 "n > 0: not evaluated\n");
  EXPECT_EQ(Session->getCycle(), 3u);
}

TEST_F(RunTest, CoverageCountsCallsStatementsAndBothWaysOfConditions) {
  Coverage = true;
  ASSERT_TRUE(load(Counter, "main")) << messages();
  RunOptions Opts;
  Opts.Cycles = 2;
  ASSERT_EQ(run(Opts), "");
  std::vector<uint64_t> Counts = readCoverage(*Loaded);
  ASSERT_EQ(Counts.size(), Loaded->Layout.CoverageSites.size());
  auto Count = [&](CoverageSite::SiteKind K, llvm::StringRef Owner,
                   unsigned Line) -> std::optional<uint64_t> {
    for (size_t I = 0; I < Counts.size(); ++I) {
      const CoverageSite &S = Loaded->Layout.CoverageSites[I];
      if (S.Kind == K && S.Owner->getName().Name == Owner &&
          C.SM.getLineAndColumn(S.N->getLoc()).first == Line)
        return Counts[I];
    }
    return std::nullopt;
  };
  EXPECT_EQ(Count(CoverageSite::Call, "count", 1), 2u);
  EXPECT_EQ(Count(CoverageSite::Call, "idle", 7), 0u);
  EXPECT_EQ(Count(CoverageSite::Stmt, "count", 2), 1u); // Resumed after it.
  EXPECT_EQ(Count(CoverageSite::Stmt, "count", 4), 2u);
  EXPECT_EQ(Count(CoverageSite::True, "main", 12), 0u);
  EXPECT_EQ(Count(CoverageSite::False, "main", 12), 2u);

  CoverageSummary S = summarizeCoverage(C, *Loaded, Counts);
  EXPECT_EQ(S.NeverActive, std::vector<std::string>{"Behavior::idle"});
  EXPECT_EQ(S.YieldsNeverReached,
            std::vector<std::string>{"Behavior.bs:8 (Behavior::idle)"});
  // Lines 1-5, 7-8, 10-13 have counters; 7, 8 and 13 never ran.
  EXPECT_EQ(S.Lines, 11u);
  EXPECT_EQ(S.LinesHit, 8u);

  clearCoverage(*Loaded);
  for (uint64_t N : readCoverage(*Loaded))
    EXPECT_EQ(N, 0u);
}

TEST_F(RunTest, WithoutCoverageThereAreNoCounters) {
  ASSERT_TRUE(load(Counter, "main")) << messages();
  EXPECT_TRUE(readCoverage(*Loaded).empty());
  EXPECT_TRUE(Loaded->Layout.CoverageSites.empty());
}

} // namespace

// `bsc replay --jobs`: a worker's result survives the pipe's encoding; a
// field a newer worker adds is skipped; a damaged record is refused.
#include "../../lib/Run/ReplayWorkers.h"
namespace {
TEST(ReplayWorkersTest, ResultsRoundTrip) {
  LogResult R;
  R.Passed = false;
  R.Cycles = 123456;
  R.Seconds = 0.25;
  R.Report = std::string("error: x\n\0y", 11);
  R.Coverage = {0, 7, uint64_t(1) << 40};
  std::string Encoded = encodeResult(R);
  LogResult Back;
  ASSERT_TRUE(decodeResult(Encoded, Back));
  EXPECT_FALSE(Back.Passed);
  EXPECT_EQ(123456u, Back.Cycles);
  EXPECT_EQ(0.25, Back.Seconds);
  EXPECT_EQ(R.Report, Back.Report);
  EXPECT_EQ(R.Coverage, Back.Coverage);
  // A field of tag 200 (3 bytes) from a newer worker.
  std::string Newer = Encoded + std::string("\xc8\x03\0\0\0abc", 8);
  ASSERT_TRUE(decodeResult(Newer, Back));
  EXPECT_EQ(R.Report, Back.Report);
  EXPECT_FALSE(decodeResult(llvm::StringRef(Encoded).drop_back(1), Back));
  EXPECT_FALSE(decodeResult(std::string("\x02\x02\0\0\0ab", 7), Back));
}
} // namespace

TEST(OutputComparisonTest, IgnoredAndTolerantMembers) {
  OutputComparison C;
  C.Ignore = {"motion", "output.head"};
  C.Tolerance = {{"walkTarget", 0.5}};
  auto D = [](const char *Path, const char *Recorded, const char *Got) {
    return debug::Difference{Path, Recorded, Got};
  };
  EXPECT_FALSE(C.counts(D("output.motion", "\"walk\"", "\"kick\"")));
  EXPECT_FALSE(C.counts(D("output.head[1]", "1", "2")));
  EXPECT_TRUE(C.counts(D("output.headTarget.y", "5", "0"))); // Not a prefix.
  EXPECT_FALSE(C.counts(D("output.walkTarget.x", "1", "1.5")));
  EXPECT_TRUE(C.counts(D("output.walkTarget.x", "1", "1.6")));
  EXPECT_TRUE(C.counts(D("output.walkTarget.x", "1", "\"far\"")));
  EXPECT_TRUE(C.counts(D("output.speed", "1", "1.1")));
  EXPECT_TRUE(OutputComparison().isExact());
}
