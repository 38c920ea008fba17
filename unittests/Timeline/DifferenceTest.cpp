//===- DifferenceTest.cpp - the first cycle where two runs differ ---------===//
#include "TimelineImpl.h"
#include "gtest/gtest.h"

using namespace bsc;
using namespace bsc::timeline;
namespace json = llvm::json;

namespace {
CycleTask task(llvm::StringRef Name, llvm::StringRef State,
               llvm::StringRef Place, int Parent = -1) {
  CycleTask T;
  T.Name = Name;
  T.State = State;
  T.Place = Place;
  T.Parent = Parent;
  return T;
}

/// A run of `Cycles` cycles whose output.motion is `Motion(cycle)` and
/// whose one task waits at line `Line(cycle)`.
template <typename MotionFn, typename LineFn>
void build(Run &R, uint32_t Cycles, MotionFn Motion, LineFn Line) {
  RunBuilder B(R);
  for (uint32_t C = 1; C <= Cycles; ++C) {
    json::Value Out = json::Object{{"motion", Motion(C)}};
    std::string Place = "M.bs:" + std::to_string(Line(C));
    B.addCycle(C, nullptr, &Out, {task("M::main", "running", Place)});
  }
  B.finish();
}

TEST(Difference, ARunDoesNotDifferFromItself) {
  timeline::Run A;
  build(A, 100, [](uint32_t C) { return C < 50 ? "walk" : "kick"; },
        [](uint32_t C) { return C % 7; });
  EXPECT_EQ(findFirstDifference(A, A), std::nullopt);
}

TEST(Difference, TheFirstDifferingCycleNamesEverythingThatDiffers) {
  timeline::Run A, B;
  build(A, 100, [](uint32_t C) { return C < 50 ? "walk" : "kick"; },
        [](uint32_t) { return 4; });
  build(B, 100, [](uint32_t C) { return C < 40 ? "walk" : "kick"; },
        [](uint32_t C) { return C < 40 ? 4 : 6; });
  std::optional<Difference> D = findFirstDifference(A, B);
  ASSERT_TRUE(D);
  EXPECT_EQ(D->Cycle, 40u);
  ASSERT_EQ(D->Notes.size(), 2u);
  EXPECT_EQ(D->Notes[0], "task M::main: A running, M.bs:4; B running, M.bs:6");
  EXPECT_EQ(D->Notes[1], "output.motion: A \"walk\", B \"kick\"");
}

TEST(Difference, ACycleOnlyOneRunHasIsADifference) {
  timeline::Run A, B;
  build(A, 10, [](uint32_t) { return "walk"; }, [](uint32_t) { return 4; });
  build(B, 8, [](uint32_t) { return "walk"; }, [](uint32_t) { return 4; });
  std::optional<Difference> D = findFirstDifference(A, B);
  ASSERT_TRUE(D);
  EXPECT_EQ(D->Cycle, 9u);
  EXPECT_EQ(D->Notes, std::vector<std::string>{"cycle 9 is only in A"});
}

TEST(Difference, AgainstARobotLogOnlyTasksCompare) {
  timeline::Run A, B;
  build(A, 10, [](uint32_t) { return "walk"; }, [](uint32_t) { return 4; });
  build(B, 10, [](uint32_t) { return "kick"; }, [](uint32_t) { return 4; });
  B.FromRobotLog = true;
  EXPECT_EQ(findFirstDifference(A, B), std::nullopt);
}
} // namespace

namespace {
/// A replay's values are the floats themselves, a recording's their
/// shortest decimals: they are the same value.
TEST(Difference, NumbersCompareAsTheFloatsTheyAre) {
  timeline::Run A, B;
  for (auto [R, X] : {std::pair{&A, json::Value(0.1)},
                      std::pair{&B, json::Value(double(0.1f))}}) {
    RunBuilder Builder(*R);
    json::Value Out = json::Object{{"x", X}};
    Builder.addCycle(1, nullptr, &Out, {});
    Builder.finish();
  }
  EXPECT_FALSE(findFirstDifference(A, B));
  timeline::Run C;
  RunBuilder Builder(C);
  json::Value Out = json::Object{{"x", 0.2}};
  Builder.addCycle(1, nullptr, &Out, {});
  Builder.finish();
  std::optional<Difference> D = findFirstDifference(A, C);
  ASSERT_TRUE(D);
  EXPECT_EQ(D->Notes, std::vector<std::string>{"output.x: A 0.1, B 0.2"});
}
} // namespace
