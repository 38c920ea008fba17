//===- RunBuilder.cpp - a run's cycles folded into changes ----------------===//
#include "TimelineImpl.h"
#include "bsc/Debug/Values.h"
#include "llvm/ADT/STLExtras.h"
#include <algorithm>
#include <cmath>

using namespace bsc;
using namespace bsc::timeline;

static const llvm::json::Value NullValue = nullptr;

const llvm::json::Value &Series::at(uint32_t Cycle) const {
  auto It = llvm::upper_bound(ChangeCycles, Cycle);
  if (It == ChangeCycles.begin())
    return NullValue;
  return Values[It - ChangeCycles.begin() - 1];
}

const Segment *TaskLane::at(uint32_t Cycle) const {
  auto It = llvm::partition_point(
      Segments, [&](const Segment &S) { return S.End < Cycle; });
  return It != Segments.end() && It->Start <= Cycle ? &*It : nullptr;
}

bool Run::hasCycle(uint32_t Cycle) const {
  auto It = llvm::partition_point(
      Cycles, [&](const std::pair<uint32_t, uint32_t> &R) {
        return R.second < Cycle;
      });
  return It != Cycles.end() && It->first <= Cycle;
}

uint32_t Run::numCycles() const {
  uint32_t N = 0;
  for (const auto &[First, Last] : Cycles)
    N += Last - First + 1;
  return N;
}

void timeline::setValue(Series &S, uint32_t Cycle,
                        const llvm::json::Value &V) {
  // A number beyond a double's range (`1e999` in a file, which parses as
  // infinity) is kept as a recording writes infinity: the page's data is
  // JSON, which has no bare infinity.
  if (std::optional<double> D = V.getAsNumber(); D && !std::isfinite(*D))
    return setValue(S, Cycle, *D > 0 ? "Infinity" : "-Infinity");
  if (!S.Values.empty() && S.Values.back() == V)
    return;
  if (S.Values.empty() && V.kind() == llvm::json::Value::Null)
    return;
  S.ChangeCycles.push_back(Cycle);
  S.Values.push_back(V);
}

unsigned RunBuilder::valueIndex(llvm::StringRef Path) {
  auto [It, New] = RootIndex.try_emplace(Path, Sources.size());
  if (New)
    Sources.push_back({-1, false, Path.str(), {}});
  return It->second;
}

unsigned RunBuilder::laneIndex(llvm::StringRef Task) {
  auto [It, New] = LaneIndex.try_emplace(Task, R.Tasks.size());
  if (New) {
    R.Tasks.push_back({Task.str(), {}, {}});
    Lanes.emplace_back();
    FieldSetIn.emplace_back();
  }
  return It->second;
}

unsigned RunBuilder::fieldIndex(unsigned Lane, llvm::StringRef Name,
                                bool IsParam) {
  LaneKeys &Keys = Lanes[Lane];
  auto [It, New] =
      (IsParam ? Keys.Params : Keys.Locals).try_emplace(Name, Sources.size());
  if (New)
    Sources.push_back({int(Lane), IsParam, Name.str(), {}});
  return It->second;
}

void RunBuilder::beginCycle(uint32_t C) {
  Cycle = C;
  ++Generation;
  if (!R.Cycles.empty() && R.Cycles.back().second + 1 == Cycle)
    R.Cycles.back().second = Cycle;
  else
    R.Cycles.push_back({Cycle, Cycle});
}

const std::string &RunBuilder::leafName(const Source &S, unsigned Leaf) const {
  return S.Lane < 0 ? R.Leaves[Leaf].Path : R.Tasks[S.Lane].Fields[Leaf].Name;
}

unsigned RunBuilder::findLeaf(const Source &S, llvm::StringRef Leaf) {
  if (S.Lane < 0) {
    auto [It, New] = LeafIndex.try_emplace(Leaf, R.Leaves.size());
    if (New) {
      R.Leaves.push_back({Leaf.str(), {}, {}});
      LeafSetIn.push_back(0);
    }
    return It->second;
  }
  TaskLane &T = R.Tasks[S.Lane];
  LaneKeys &Keys = Lanes[S.Lane];
  auto [It, New] = (S.IsParam ? Keys.ParamLeaves : Keys.LocalLeaves)
                       .try_emplace(Leaf, T.Fields.size());
  if (New) {
    T.Fields.push_back({Leaf.str(), S.IsParam, {}});
    T.Fields.back().Values.Path = T.Name + "." + Leaf.str();
    FieldSetIn[S.Lane].push_back(0);
  }
  return It->second;
}

void RunBuilder::setValue(unsigned Value, const llvm::json::Value &V) {
  Source &S = Sources[Value];
  std::vector<uint32_t> &SetIn = S.Lane < 0 ? LeafSetIn : FieldSetIn[S.Lane];
  auto Set = [&](unsigned Leaf, const llvm::json::Value &V) {
    SetIn[Leaf] = Generation;
    timeline::setValue(S.Lane < 0 ? R.Leaves[Leaf]
                                  : R.Tasks[S.Lane].Fields[Leaf].Values,
                       Cycle, V);
  };
  // A number, bool or string that was one before: its one leaf.
  if (!V.getAsObject() && !V.getAsArray() && S.Leaves.size() == 1 &&
      leafName(S, S.Leaves[0]) == S.Name)
    return Set(S.Leaves[0], V);
  // A class or array is its leaves (`target.x`), which plot. They are
  // those of the value before, in the same order, but for a change of
  // shape (a JSON recording may have any).
  std::string Path = S.Name;
  size_t K = 0;
  debug::forEachJSONLeaf(Path, V, [&](llvm::StringRef Leaf, const llvm::json::Value &V) {
    if (K == S.Leaves.size())
      S.Leaves.push_back(findLeaf(S, Leaf));
    else if (leafName(S, S.Leaves[K]) != Leaf)
      S.Leaves[K] = findLeaf(S, Leaf);
    Set(S.Leaves[K++], V);
  });
  S.Leaves.resize(K);
}

void RunBuilder::keepValue(unsigned Value) {
  const Source &S = Sources[Value];
  std::vector<uint32_t> &SetIn = S.Lane < 0 ? LeafSetIn : FieldSetIn[S.Lane];
  for (unsigned Leaf : S.Leaves)
    SetIn[Leaf] = Generation;
}

void RunBuilder::addTask(unsigned Lane, llvm::StringRef State,
                         llvm::StringRef Place, int ParentLane) {
  // A task's segment goes on while the task keeps its state, yield and
  // parent from one cycle to the next.
  std::vector<Segment> &Segs = R.Tasks[Lane].Segments;
  if (!Segs.empty() && Segs.back().End + 1 == Cycle &&
      Segs.back().State == State && Segs.back().Place == Place &&
      Segs.back().Parent == ParentLane)
    Segs.back().End = Cycle;
  else
    Segs.push_back({Cycle, Cycle, State.str(), Place.str(), ParentLane});
}

void RunBuilder::endCycle() {
  for (size_t I = 0; I < R.Leaves.size(); ++I)
    if (LeafSetIn[I] != Generation)
      timeline::setValue(R.Leaves[I], Cycle, nullptr);
  for (size_t L = 0; L < R.Tasks.size(); ++L)
    for (size_t F = 0; F < R.Tasks[L].Fields.size(); ++F)
      if (FieldSetIn[L][F] != Generation)
        timeline::setValue(R.Tasks[L].Fields[F].Values, Cycle, nullptr);
}

void RunBuilder::setFields(unsigned Lane, const llvm::json::Object *Fields,
                           bool IsParam) {
  if (Fields)
    for (const auto &KV : *Fields)
      setValue(fieldIndex(Lane, KV.first, IsParam), KV.second);
}

void RunBuilder::addCycle(uint32_t C, const llvm::json::Value *Input,
                          const llvm::json::Value *Output,
                          llvm::ArrayRef<CycleTask> Tasks) {
  beginCycle(C);
  if (Input)
    setValue(valueIndex("input"), *Input);
  if (Output)
    setValue(valueIndex("output"), *Output);
  std::vector<unsigned> LaneOfTask;
  for (const CycleTask &T : Tasks) {
    unsigned L = laneIndex(T.Name);
    LaneOfTask.push_back(L);
    addTask(L, T.State, T.Place, T.Parent < 0 ? -1 : int(LaneOfTask[T.Parent]));
    setFields(L, T.Params, /*IsParam=*/true);
    setFields(L, T.Locals, /*IsParam=*/false);
  }
  endCycle();
}

void RunBuilder::finish() {
  llvm::sort(R.Leaves, [](const Series &A, const Series &B) {
    return A.Path < B.Path;
  });
  // A JSON object keeps no order: parameters first, then locals, by name.
  for (TaskLane &T : R.Tasks)
    llvm::sort(T.Fields, [](const TaskLane::Field &A, const TaskLane::Field &B) {
      return std::make_pair(!A.IsParam, llvm::StringRef(A.Name)) <
             std::make_pair(!B.IsParam, llvm::StringRef(B.Name));
    });
}
