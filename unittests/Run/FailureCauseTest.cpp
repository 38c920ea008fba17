//===- FailureCauseTest.cpp - the first task a failed replay differs in ---===//
#include "FailureCause.h"
#include "gtest/gtest.h"

using namespace bsc;

namespace {
const std::vector<ActiveTaskView> Recorded = {
    {"B::main", "running", "B.bs:10", ""},
    {"B::walk", "running", "B.bs:3", "B::main"},
    {"H::look", "running", "H.bs:4", "B::main"}};

TEST(FailureCause, TheSameTasksDoNotDiffer) {
  EXPECT_FALSE(findTaskDifference(Recorded, Recorded));
  EXPECT_FALSE(findTaskDifference({}, {}));
}

/// Another yield or state: the task itself explains it.
TEST(FailureCause, AnotherYieldIsTheTasksOwn) {
  std::vector<ActiveTaskView> Replayed = Recorded;
  Replayed[1].Place = "B.bs:5";
  Replayed[2].State = "done";
  std::optional<TaskDifference> D = findTaskDifference(Recorded, Replayed);
  ASSERT_TRUE(D);
  EXPECT_EQ(D->Task, "B::walk"); // The first, in the recording's order.
  EXPECT_EQ(D->Recorded, "running at B.bs:3 under B::main");
  EXPECT_EQ(D->Replayed, "running at B.bs:5 under B::main");
  EXPECT_EQ(D->Explains, "B::walk");
}

/// A task one side calls and the other does not, or under another
/// caller: the caller chose, so the caller explains it.
TEST(FailureCause, ACallOrAParentIsTheCallers) {
  std::vector<ActiveTaskView> Replayed = {Recorded[0], Recorded[2]};
  std::optional<TaskDifference> D = findTaskDifference(Recorded, Replayed);
  ASSERT_TRUE(D);
  EXPECT_EQ(D->Task, "B::walk");
  EXPECT_EQ(D->Replayed, "not active");
  EXPECT_EQ(D->Explains, "B::main");

  Replayed = Recorded;
  Replayed.push_back({"B::kick", "done", "", "B::main"});
  D = findTaskDifference(Recorded, Replayed);
  ASSERT_TRUE(D);
  EXPECT_EQ(D->Task, "B::kick");
  EXPECT_EQ(D->Recorded, "not active");
  EXPECT_EQ(D->Replayed, "done under B::main");
  EXPECT_EQ(D->Explains, "B::main");

  Replayed = Recorded;
  Replayed[2].Parent = "B::walk";
  D = findTaskDifference(Recorded, Replayed);
  ASSERT_TRUE(D);
  EXPECT_EQ(D->Task, "H::look");
  EXPECT_EQ(D->Explains, "B::walk");
}
} // namespace
