//===- DebugSessionTest.cpp - the REPL's session for the debug adapter ----===//
//
// DebugSession (bsc/REPL/DebugSession.h) on a behavior without bindings:
// breakpoints and their verification, hit conditions, the run commands
// by cycles and back in time, frames of the hierarchy, values, lines.
//
//===----------------------------------------------------------------------===//
#include "bsc/REPL/DebugSession.h"
#include "ReplImpl.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/Path.h"
#include "llvm/Support/raw_ostream.h"
#include "gtest/gtest.h"

using namespace bsc;

namespace {

// main counts its cycles; flip fails in cycle 3; step waits one cycle in
// two.
const char *Behavior = R"(task flip(int n)
    if(n == 3)
        yield TaskState::failure

task step(int n)
    int twice = n * 2
    yield
    twice += 1

task main()
    int n = 0
    for(;; yield)
        n += 1
        flip(n)
        step(n)
)";

class DebugSessionTest : public ::testing::Test {
protected:
  void SetUp() override { load(Behavior); }
  void load(const char *Source) {
    Session.reset();
    if (Dir.empty()) {
      ASSERT_FALSE(
          llvm::sys::fs::createUniqueDirectory("debug-session", Dir));
    }
    File.clear();
    llvm::sys::path::append(File, Dir, "Counter.bs");
    std::error_code EC;
    llvm::raw_fd_ostream OS(File, EC);
    ASSERT_FALSE(EC);
    OS << Source;
    OS.close();
    Opts.Frontend.Inputs = {File.str().str()};
    std::string Errors;
    Session = DebugSession::start(Opts, "", Errors);
    ASSERT_TRUE(Session) << Errors;
  }
  void TearDown() override {
    Session.reset();
    llvm::sys::fs::remove_directories(Dir);
  }
  int64_t value(llvm::StringRef Expr) {
    std::optional<DebugValue> V = Session->evaluate(Expr, 0, std::nullopt);
    EXPECT_TRUE(V) << Session->takeErrors();
    return V ? V->Value.getAsInteger().value_or(-1) : -1;
  }

  llvm::SmallString<128> Dir, File;
  ReplOptions Opts;
  std::unique_ptr<DebugSession> Session;
};

TEST(HitConditionTest, ParsesTheFormsAndCountsHits) {
  using repl::HitCondition;
  EXPECT_EQ(HitCondition::parse("5")->Operator, HitCondition::AtLeast);
  EXPECT_EQ(HitCondition::parse(" == 3 ")->Operator, HitCondition::Equal);
  EXPECT_EQ(HitCondition::parse(">4")->N, 4u);
  EXPECT_FALSE(HitCondition::parse("often"));
  EXPECT_FALSE(HitCondition::parse("% 0"));
  EXPECT_FALSE(HitCondition::parse(">= -1"));
  EXPECT_FALSE(HitCondition::parse(""));
  HitCondition Every2 = *HitCondition::parse("% 2");
  EXPECT_FALSE(Every2.stopsAt(1));
  EXPECT_TRUE(Every2.stopsAt(2));
  EXPECT_TRUE(HitCondition::parse(">= 2")->stopsAt(3));
  EXPECT_FALSE(HitCondition::parse("== 2")->stopsAt(3));
  EXPECT_TRUE(HitCondition().stopsAt(1));
}

TEST_F(DebugSessionTest, BreakpointsAreVerifiedAgainstTheLinesThatRun) {
  std::vector<BreakpointState> States =
      Session->setSourceBreakpoints(File, {{7, "", "", ""},
                                           {8, "", "", ""},
                                           {9, "", "", ""},
                                           {5, "", "", ""},
                                           {8, "n +", "", ""},
                                           {8, "", "x", ""}});
  ASSERT_EQ(States.size(), 6u);
  EXPECT_TRUE(States[0].Verified);  // A yield.
  EXPECT_TRUE(States[1].Verified);  // A statement.
  EXPECT_FALSE(States[2].Verified); // Empty.
  EXPECT_TRUE(States[3].Verified);  // A task's first line.
  EXPECT_FALSE(States[4].Verified);
  EXPECT_NE(States[4].Message.find("expected an expression"),
            std::string::npos);
  EXPECT_FALSE(States[5].Verified);
  // Numbers follow the REPL's, without gaps for those refused.
  EXPECT_EQ(States[1].Id, States[0].Id + 1);
  EXPECT_EQ(States[3].Id, States[1].Id + 1);
  // Replacing a file's breakpoints removes the old ones.
  EXPECT_TRUE(Session->setSourceBreakpoints(File, {}).empty());
  DebugStop Stop = Session->run(DebugRun::Next, nullptr);
  EXPECT_EQ(Stop.Why, DebugStop::Step);
  EXPECT_EQ(Session->getCycle(), 1u);
}

TEST_F(DebugSessionTest, ContinueStopsAtALineWithItsConditionAndHitCount) {
  // `twice += 1` runs in the even cycles. Hits count where the condition
  // (`n > 2`, step's parameter) holds: cycles 4 and 6; every second stops.
  std::vector<BreakpointState> States =
      Session->setSourceBreakpoints(File, {{8, "n > 2", "% 2", ""}});
  ASSERT_TRUE(States[0].Verified) << States[0].Message;
  DebugStop Stop = Session->run(DebugRun::Continue, nullptr);
  EXPECT_EQ(Stop.Why, DebugStop::Breakpoint);
  EXPECT_EQ(Session->getCycle(), 6u);
  EXPECT_EQ(value("main.n"), 6);
  EXPECT_EQ(Stop.Breakpoints, std::vector<unsigned>{States[0].Id});
}

// The tasks in the order `:tasks` lists them (the task table's), reversed.
TEST_F(DebugSessionTest, FramesAreTheHierarchyWithTheLastBranchOnTop) {
  std::vector<DebugFrame> Frames = Session->getFrames(0);
  ASSERT_EQ(Frames.size(), 1u);
  EXPECT_NE(Frames[0].Name.find("before the first cycle"), std::string::npos);
  Session->run(DebugRun::Next, nullptr);
  Frames = Session->getFrames(0);
  ASSERT_EQ(Frames.size(), 3u);
  EXPECT_EQ(Frames[0].Name, "main > step [running, Counter.bs:7]");
  EXPECT_EQ(Frames[0].Line, 7u);
  EXPECT_TRUE(Frames[0].Waiting);
  EXPECT_EQ(Frames[1].Name, "main > flip [done]");
  EXPECT_EQ(Frames[2].Name, "main [running, Counter.bs:12]");
  EXPECT_EQ(Frames[2].Path, File.str());
  std::vector<DebugValue> Fields = Session->getFields(0, Frames[0]);
  ASSERT_EQ(Fields.size(), 2u);
  EXPECT_EQ(Fields[0].Name, "n");
  EXPECT_EQ(Fields[1].Display, "2");
  EXPECT_EQ(Fields[1].Path, "step.twice");
  // A finished task keeps its parameters only.
  EXPECT_EQ(Session->getFields(0, Frames[1]).size(), 1u);
  // Evaluated in step's frame, its locals are unqualified.
  std::optional<DebugValue> V =
      Session->evaluate("twice + n", 0, Frames[0].Task);
  ASSERT_TRUE(V);
  EXPECT_EQ(V->Display, "3");
  EXPECT_FALSE(Session->evaluate("twice", 0, std::nullopt));
  EXPECT_NE(Session->takeErrors().find("twice"), std::string::npos);
}

TEST_F(DebugSessionTest, SteppingByCyclesAndBackInTime) {
  Session->run(DebugRun::Next, nullptr);
  // Step out of step: it ends in cycle 2 (after its yield).
  DebugStop Out = Session->run(DebugRun::StepOut, nullptr);
  EXPECT_EQ(Session->getCycle(), 2u);
  EXPECT_EQ(Out.Description, "main > step [done]");
  // Step in: cycle 3 runs `int twice = n * 2` again (not in cycle 2).
  DebugStop In = Session->run(DebugRun::StepIn, nullptr);
  EXPECT_EQ(Session->getCycle(), 3u);
  EXPECT_EQ(In.Why, DebugStop::Step);
  // The task-failure filter stops at flip's failure: cycle 3 is past it.
  EXPECT_EQ(Session->setExceptionFilters({"taskFailure", "x"}),
            "no exception filter 'x' (assertion, taskFailure, budget)");
  EXPECT_EQ(Session->setExceptionFilters({"taskFailure"}), "");
  DebugStop Back = Session->run(DebugRun::StepBack, nullptr);
  EXPECT_EQ(Session->getCycle(), 2u);
  EXPECT_EQ(value("main.n"), 2);
  DebugStop Fails = Session->run(DebugRun::Continue, nullptr);
  EXPECT_EQ(Fails.Why, DebugStop::Exception);
  EXPECT_EQ(Fails.ExceptionId, "taskFailure");
  EXPECT_EQ(Fails.Description, "Counter::flip failed");
  EXPECT_EQ(Session->getCycle(), 3u);
  // Reverse continue with a breakpoint on flip: the cycle before.
  Session->setExceptionFilters({});
  Session->setTaskBreakpoints({{"flip", "", ""}});
  DebugStop Reverse = Session->run(DebugRun::ReverseContinue, nullptr);
  EXPECT_EQ(Reverse.Why, DebugStop::Breakpoint);
  EXPECT_EQ(Session->getCycle(), 2u);
  ASSERT_TRUE(Session->gotoCycle(7));
  EXPECT_EQ(value("main.n"), 7);
  EXPECT_FALSE(Session->gotoCycle(uint32_t(-1)));
  Session->takeErrors();
  (void)Back;
}

TEST_F(DebugSessionTest, PauseStopsARun) {
  unsigned Asked = 0;
  DebugStop Stop =
      Session->run(DebugRun::Continue, [&] { return ++Asked == 5; });
  EXPECT_EQ(Stop.Why, DebugStop::Pause);
  EXPECT_EQ(Session->getCycle(), 5u);
}

TEST_F(DebugSessionTest, SetInputIsOnlyForInput) {
  EXPECT_FALSE(Session->setInput("main.n", "3", 0));
  EXPECT_NE(Session->takeErrors().find("only members of input"),
            std::string::npos);
  // No world module: no input at all.
  EXPECT_FALSE(Session->getInput(0));
  EXPECT_FALSE(Session->setInput("input.x", "3", 0));
}

TEST_F(DebugSessionTest, AnAssumptionThatDoesNotHoldStopsAsAnException) {
  load("task main()\n    int n = 0\n    for(;; yield)\n        n += 1\n"
       "        assume(n < 3)\n");
  DebugStop Stop = Session->run(DebugRun::Continue, nullptr);
  EXPECT_EQ(Stop.Why, DebugStop::Exception);
  EXPECT_EQ(Stop.ExceptionId, "assertion");
  EXPECT_EQ(Stop.Description, "an assumption does not hold");
  EXPECT_EQ(Session->getCycle(), 3u);
  EXPECT_NE(Session->takeErrors().find("assumption does not hold: n < 3"),
            std::string::npos);
  // Without the filter, the run goes on (to a pause here).
  Session->setExceptionFilters({});
  unsigned Asked = 0;
  Stop = Session->run(DebugRun::Continue, [&] { return ++Asked == 4; });
  EXPECT_EQ(Stop.Why, DebugStop::Pause);
  EXPECT_EQ(Session->getCycle(), 7u); // Asked after cycles 4 to 7.
}

} // namespace
