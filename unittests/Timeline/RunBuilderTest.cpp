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

namespace {
/// What a replay feeds (CycleSink): values set, kept or left out, tasks
/// by lane. A kept value is the cycle before's; one left out is absent.
TEST(RunBuilder, ASinkKeepsWhatIsKeptAndDropsWhatIsNot) {
  timeline::Run R;
  RunBuilder B(R);
  CycleSink &S = B;
  unsigned Time = S.valueIndex("input.time");
  unsigned Main = S.laneIndex("M::main");
  unsigned Walk = S.laneIndex("M::walk");
  unsigned N = S.fieldIndex(Walk, "n", /*IsParam=*/false);
  unsigned Target = S.fieldIndex(Walk, "target", /*IsParam=*/true);
  EXPECT_EQ(S.laneIndex("M::walk"), Walk);
  EXPECT_EQ(S.fieldIndex(Walk, "n", false), N);
  EXPECT_NE(S.fieldIndex(Walk, "n", true), N); // A parameter n is another.

  S.beginCycle(1);
  S.setValue(Time, 10);
  S.addTask(Main, "running", "M.bs:4", -1);
  S.addTask(Walk, "running", "M.bs:8", int(Main));
  S.setValue(N, 1);
  S.setValue(Target, json::Object{{"x", 5}, {"y", 6}});
  S.endCycle();
  S.beginCycle(2); // Everything kept.
  S.keepValue(Time);
  S.addTask(Main, "running", "M.bs:4", -1);
  S.addTask(Walk, "running", "M.bs:8", int(Main));
  S.keepValue(N);
  S.keepValue(Target);
  S.endCycle();
  S.beginCycle(3); // walk has finished: its local is gone.
  S.setValue(Time, 30);
  S.addTask(Main, "running", "M.bs:4", -1);
  S.addTask(Walk, "done", "", int(Main));
  S.keepValue(Target);
  S.endCycle();
  S.beginCycle(4); // walk is not active; input.time is not set.
  S.addTask(Main, "running", "M.bs:5", -1);
  S.endCycle();
  B.finish();

  ASSERT_EQ(R.Leaves.size(), 1u);
  EXPECT_EQ(R.Leaves[0].Path, "input.time");
  EXPECT_EQ(R.Leaves[0].ChangeCycles, (std::vector<uint32_t>{1, 3, 4}));
  EXPECT_EQ(R.Leaves[0].at(2), json::Value(10));
  EXPECT_EQ(R.Leaves[0].at(4), json::Value(nullptr));
  const TaskLane &W = R.Tasks[Walk];
  ASSERT_EQ(W.Fields.size(), 3u);
  // Parameters first: target.x, target.y, then the local n.
  EXPECT_EQ(W.Fields[0].Values.Path, "M::walk.target.x");
  EXPECT_EQ(W.Fields[0].Values.ChangeCycles, (std::vector<uint32_t>{1, 4}));
  EXPECT_EQ(W.Fields[0].Values.at(3), json::Value(5));
  EXPECT_EQ(W.Fields[2].Name, "n");
  EXPECT_EQ(W.Fields[2].Values.at(2), json::Value(1));
  EXPECT_EQ(W.Fields[2].Values.at(3), json::Value(nullptr));
  ASSERT_EQ(W.Segments.size(), 2u);
  EXPECT_EQ(W.Segments[0].Parent, int(Main));
  EXPECT_EQ(W.Segments[1].State, "done");
  EXPECT_EQ(R.Tasks[Main].Segments.size(), 2u);
}

/// A value whose shape changes (a recording may hold anything) is its new
/// leaves; the old ones are absent from then on.
TEST(RunBuilder, AValueOfAnotherShapeIsItsNewLeaves) {
  timeline::Run R;
  RunBuilder B(R);
  json::Value Out1 = json::Object{{"a", 1}};
  json::Value Out2 = json::Object{{"b", json::Array{2, 3}}};
  json::Value Out3 = json::Object{{"a", 4}, {"b", json::Array{2, 3}}};
  B.addCycle(1, nullptr, &Out1, {});
  B.addCycle(2, nullptr, &Out2, {});
  B.addCycle(3, nullptr, &Out3, {});
  B.finish();
  ASSERT_EQ(R.Leaves.size(), 3u);
  EXPECT_EQ(R.Leaves[0].Path, "output.a");
  EXPECT_EQ(R.Leaves[0].at(2), json::Value(nullptr));
  EXPECT_EQ(R.Leaves[0].at(3), json::Value(4));
  EXPECT_EQ(R.Leaves[2].Path, "output.b[1]");
  EXPECT_EQ(R.Leaves[2].at(1), json::Value(nullptr));
  EXPECT_EQ(R.Leaves[2].at(3), json::Value(3));
}
} // namespace
