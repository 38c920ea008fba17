//===- RunBuilder.cpp - a run's cycles folded into changes ----------------===//
#include "TimelineImpl.h"
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

/// Calls `Leaf` with the path and value of each number, string, bool or
/// null in `V`: `.member` for an object's members, `[i]` for elements.
static void forEachLeaf(
    std::string &Path, const llvm::json::Value &V,
    llvm::function_ref<void(llvm::StringRef, const llvm::json::Value &)> Leaf) {
  size_t Length = Path.size();
  if (const llvm::json::Object *O = V.getAsObject()) {
    for (const auto &KV : *O) {
      (Path += ".") += llvm::StringRef(KV.first);
      forEachLeaf(Path, KV.second, Leaf);
      Path.resize(Length);
    }
    return;
  }
  if (const llvm::json::Array *A = V.getAsArray()) {
    for (size_t I = 0; I < A->size(); ++I) {
      ((Path += "[") += std::to_string(I)) += "]";
      forEachLeaf(Path, (*A)[I], Leaf);
      Path.resize(Length);
    }
    return;
  }
  Leaf(Path, V);
}

void RunBuilder::addLeaves(std::string &Path, const llvm::json::Value &V,
                           uint32_t Cycle) {
  forEachLeaf(Path, V, [&](llvm::StringRef Leaf, const llvm::json::Value &V) {
    auto [It, New] = LeafIndex.try_emplace(Leaf, R.Leaves.size());
    if (New) {
      R.Leaves.push_back({Leaf.str(), {}, {}});
      LeafSetIn.push_back(0);
    }
    setValue(R.Leaves[It->second], Cycle, V);
    LeafSetIn[It->second] = Cycle;
  });
}

unsigned RunBuilder::laneFor(llvm::StringRef Task) {
  auto [It, New] = LaneIndex.try_emplace(Task, R.Tasks.size());
  if (New) {
    R.Tasks.push_back({Task.str(), {}, {}});
    FieldIndex.emplace_back();
    FieldSetIn.emplace_back();
  }
  return It->second;
}

void RunBuilder::addFields(unsigned Lane, const llvm::json::Object *Fields,
                           bool IsParam, uint32_t Cycle) {
  if (!Fields)
    return;
  TaskLane &T = R.Tasks[Lane];
  // A class or array field is its leaves (`target.x`), which plot.
  std::string Path;
  for (const auto &KV : *Fields) {
    Path = KV.first.str();
    forEachLeaf(Path, KV.second,
                [&](llvm::StringRef Name, const llvm::json::Value &V) {
                  auto [It, New] = FieldIndex[Lane].try_emplace(
                      (IsParam ? "p" : "l") + Name.str(), T.Fields.size());
                  if (New) {
                    T.Fields.push_back({Name.str(), IsParam, {}});
                    T.Fields.back().Values.Path = T.Name + "." + Name.str();
                    FieldSetIn[Lane].push_back(0);
                  }
                  setValue(T.Fields[It->second].Values, Cycle, V);
                  FieldSetIn[Lane][It->second] = Cycle;
                });
  }
}

void RunBuilder::addCycle(uint32_t Cycle, const llvm::json::Value *Input,
                          const llvm::json::Value *Output,
                          llvm::ArrayRef<CycleTask> Tasks) {
  if (!R.Cycles.empty() && R.Cycles.back().second + 1 == Cycle)
    R.Cycles.back().second = Cycle;
  else
    R.Cycles.push_back({Cycle, Cycle});

  std::string Path;
  if (Input) {
    Path = "input";
    addLeaves(Path, *Input, Cycle);
  }
  if (Output) {
    Path = "output";
    addLeaves(Path, *Output, Cycle);
  }
  for (size_t I = 0; I < R.Leaves.size(); ++I)
    if (LeafSetIn[I] != Cycle)
      setValue(R.Leaves[I], Cycle, nullptr);

  // A task's segment goes on while the task keeps its state, yield and
  // parent from one cycle to the next.
  std::vector<unsigned> LaneOfTask;
  for (const CycleTask &T : Tasks) {
    unsigned L = laneFor(T.Name);
    LaneOfTask.push_back(L);
    int Parent = T.Parent < 0 ? -1 : int(LaneOfTask[T.Parent]);
    std::vector<Segment> &Segs = R.Tasks[L].Segments;
    if (!Segs.empty() && Segs.back().End + 1 == Cycle &&
        Segs.back().State == T.State && Segs.back().Place == T.Place &&
        Segs.back().Parent == Parent)
      Segs.back().End = Cycle;
    else
      Segs.push_back({Cycle, Cycle, T.State.str(), T.Place.str(), Parent});
    addFields(L, T.Params, /*IsParam=*/true, Cycle);
    addFields(L, T.Locals, /*IsParam=*/false, Cycle);
  }
  for (size_t L = 0; L < R.Tasks.size(); ++L)
    for (size_t F = 0; F < R.Tasks[L].Fields.size(); ++F)
      if (FieldSetIn[L][F] != Cycle)
        setValue(R.Tasks[L].Fields[F].Values, Cycle, nullptr);
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
