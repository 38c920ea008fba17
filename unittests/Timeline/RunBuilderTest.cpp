//===- RunBuilderTest.cpp - cycles folded into segments and changes -------===//
#include "TimelineImpl.h"
#include "gtest/gtest.h"

using namespace bsc;
using namespace bsc::timeline;
namespace json = llvm::json;

namespace {
/// A cycle's tasks in the form a reader hands them over.
CycleTask task(llvm::StringRef Name, llvm::StringRef State,
               llvm::StringRef Place, int Parent = -1,
               const json::Object *Locals = nullptr) {
  CycleTask T;
  T.Name = Name;
  T.State = State;
  T.Place = Place;
  T.Parent = Parent;
  T.Locals = Locals;
  return T;
}

TEST(RunBuilder, ConsecutiveCyclesInOneStateAreOneSegment) {
  timeline::Run R;
  RunBuilder B(R);
  for (uint32_t C = 1; C <= 3; ++C)
    B.addCycle(C, nullptr, nullptr, {task("M::main", "running", "M.bs:4")});
  B.addCycle(4, nullptr, nullptr, {task("M::main", "running", "M.bs:6")});
  B.finish();
  ASSERT_EQ(R.Tasks.size(), 1u);
  const std::vector<Segment> &S = R.Tasks[0].Segments;
  ASSERT_EQ(S.size(), 2u);
  EXPECT_EQ(S[0].Start, 1u);
  EXPECT_EQ(S[0].End, 3u);
  EXPECT_EQ(S[1].Start, 4u);
  EXPECT_EQ(S[1].Place, "M.bs:6");
  EXPECT_EQ(R.Cycles, (std::vector<std::pair<uint32_t, uint32_t>>{{1, 4}}));
}

TEST(RunBuilder, ANewParentOrAGapStartsASegment) {
  timeline::Run R;
  RunBuilder B(R);
  B.addCycle(1, nullptr, nullptr,
             {task("M::a", "running", "M.bs:1"),
              task("M::c", "running", "M.bs:9", 0)});
  B.addCycle(2, nullptr, nullptr,
             {task("M::b", "running", "M.bs:5"),
              task("M::c", "running", "M.bs:9", 0)});
  // Cycle 3 is not in the run: the segment after it is another.
  B.addCycle(4, nullptr, nullptr,
             {task("M::b", "running", "M.bs:5"),
              task("M::c", "running", "M.bs:9", 0)});
  B.finish();
  ASSERT_EQ(R.Tasks.size(), 3u);
  const TaskLane &C = R.Tasks[1];
  ASSERT_EQ(C.Name, "M::c");
  ASSERT_EQ(C.Segments.size(), 3u);
  EXPECT_EQ(C.Segments[0].Parent, 0); // M::a
  EXPECT_EQ(C.Segments[1].Parent, 2); // M::b
  EXPECT_EQ(C.Segments[2].Start, 4u);
  EXPECT_EQ(C.at(3), nullptr);
  EXPECT_EQ(C.at(4), &C.Segments[2]);
  EXPECT_FALSE(R.hasCycle(3));
  EXPECT_EQ(R.numCycles(), 3u);
}

TEST(RunBuilder, LeavesAreChangesAndAbsentIsNull) {
  timeline::Run R;
  RunBuilder B(R);
  json::Value In1 = json::Object{{"ball", json::Object{{"x", 1}}}};
  json::Value In2 = json::Object{{"ball", json::Object{{"x", 1}}}};
  json::Value In3 = json::Object{{"ball", json::Object{{"x", 2}}},
                                 {"wide", json::Array{7, 8}}};
  B.addCycle(1, &In1, nullptr, {});
  B.addCycle(2, &In2, nullptr, {});
  B.addCycle(3, &In3, nullptr, {});
  B.addCycle(4, &In2, nullptr, {});
  B.finish();
  ASSERT_EQ(R.Leaves.size(), 3u); // Sorted by path.
  const Series &X = R.Leaves[0];
  EXPECT_EQ(X.Path, "input.ball.x");
  EXPECT_EQ(X.ChangeCycles, (std::vector<uint32_t>{1, 3, 4}));
  EXPECT_EQ(X.at(2), json::Value(1));
  EXPECT_EQ(X.at(3), json::Value(2));
  EXPECT_EQ(X.at(0), json::Value(nullptr));
  const Series &Wide1 = R.Leaves[2];
  EXPECT_EQ(Wide1.Path, "input.wide[1]");
  EXPECT_EQ(Wide1.at(3), json::Value(8));
  // Absent from cycle 4's line: null from then on.
  EXPECT_EQ(Wide1.at(4), json::Value(nullptr));
}

TEST(RunBuilder, TaskFieldsAreLeavesWhileTheTaskRuns) {
  timeline::Run R;
  RunBuilder B(R);
  json::Object Locals{{"target", json::Object{{"x", 5}, {"y", 6}}},
                      {"n", 1}};
  B.addCycle(1, nullptr, nullptr,
             {task("M::walk", "running", "M.bs:2", -1, &Locals)});
  B.addCycle(2, nullptr, nullptr, {});
  B.finish();
  const TaskLane &W = R.Tasks[0];
  ASSERT_EQ(W.Fields.size(), 3u);
  // Sorted by name: n, target.x, target.y.
  EXPECT_EQ(W.Fields[0].Name, "n");
  EXPECT_EQ(W.Fields[1].Name, "target.x");
  EXPECT_EQ(W.Fields[1].Values.Path, "M::walk.target.x");
  EXPECT_EQ(W.Fields[1].Values.at(1), json::Value(5));
  EXPECT_EQ(W.Fields[1].Values.at(2), json::Value(nullptr));
}
} // namespace
