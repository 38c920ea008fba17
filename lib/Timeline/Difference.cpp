//===- Difference.cpp - the first cycle where two runs differ -------------===//
//
// Between two cycles where nothing changes in either run, the runs agree or
// disagree alike; so only the cycles where something changes in one of them
// (a value, a segment's start or end, a range of cycles) need comparing.
// The first of them where anything differs is the first difference; every
// leaf, task and field that differs there is a note, as a replay names
// every output member that differs.
//
//===----------------------------------------------------------------------===//
#include "TimelineImpl.h"
#include "bsc/Debug/Values.h"
#include "bsc/Frontend/Frontend.h"
#include "llvm/ADT/STLExtras.h"
#include <map>
#include <set>

using namespace bsc;
using namespace bsc::timeline;

namespace {
/// The things the two runs hold, matched by name: a leaf, task or field
/// only one run has is paired with nothing.
struct Pairs {
  std::vector<std::pair<const Series *, const Series *>> Values;
  std::vector<std::pair<const TaskLane *, const TaskLane *>> Tasks;

  Pairs(const Run &A, const Run &B) {
    std::map<std::string, std::pair<const Series *, const Series *>> ByPath;
    std::map<std::string, std::pair<const TaskLane *, const TaskLane *>>
        ByName;
    auto Add = [&](const Run &R, bool First) {
      auto Put = [&](auto &Pair, auto *What) {
        (First ? Pair.first : Pair.second) = What;
      };
      for (const Series &S : R.Leaves)
        Put(ByPath[S.Path], &S);
      for (const TaskLane &T : R.Tasks) {
        Put(ByName[T.Name], &T);
        for (const TaskLane::Field &F : T.Fields)
          Put(ByPath[F.Values.Path], &F.Values);
      }
    };
    Add(A, true);
    Add(B, false);
    // Tasks first: a task in another state explains the values it wrote.
    for (const auto &KV : ByName)
      Tasks.push_back(KV.second);
    for (const auto &KV : ByPath)
      Values.push_back(KV.second);
  }
};

/// The cycles where something changes in `R`.
void addChangeCycles(const Run &R, std::set<uint32_t> &Cycles) {
  for (const auto &[First, Last] : R.Cycles) {
    Cycles.insert(First);
    Cycles.insert(Last + 1);
  }
  auto AddSeries = [&](const Series &S) {
    Cycles.insert(S.ChangeCycles.begin(), S.ChangeCycles.end());
  };
  for (const Series &S : R.Leaves)
    AddSeries(S);
  for (const TaskLane &T : R.Tasks) {
    for (const Segment &S : T.Segments) {
      Cycles.insert(S.Start);
      Cycles.insert(S.End + 1);
    }
    for (const TaskLane::Field &F : T.Fields)
      AddSeries(F.Values);
  }
}

std::string describeValue(const llvm::json::Value &V) {
  return V.kind() == llvm::json::Value::Null ? "absent"
                                             : debug::toJSONString(V);
}

/// `running, Kick.bs:10 under Kick::main`, or `not active`.
std::string describeTask(const Run &R, const Segment *S) {
  if (!S)
    return "not active";
  std::string Text = S->State;
  if (!S->Place.empty())
    Text += ", " + S->Place;
  if (S->Parent >= 0)
    Text += " under " + R.Tasks[S->Parent].Name;
  return Text;
}

const Segment *segmentAt(const TaskLane *T, uint32_t Cycle) {
  return T ? T->at(Cycle) : nullptr;
}

/// What differs between the runs in `Cycle`, present in both.
std::vector<std::string> compareCycle(const Run &A, const Run &B,
                                      const Pairs &P, uint32_t Cycle) {
  std::vector<std::string> Notes;
  for (const auto &[TA, TB] : P.Tasks) {
    const Segment *SA = segmentAt(TA, Cycle), *SB = segmentAt(TB, Cycle);
    if (!SA && !SB)
      continue;
    if (SA && SB && SA->State == SB->State && SA->Place == SB->Place &&
        (SA->Parent < 0) == (SB->Parent < 0) &&
        (SA->Parent < 0 ||
         A.Tasks[SA->Parent].Name == B.Tasks[SB->Parent].Name))
      continue;
    Notes.push_back("task " + (TA ? TA : TB)->Name + ": A " +
                    describeTask(A, SA) + "; B " + describeTask(B, SB));
  }
  // A robot's log has no values to compare with.
  if (A.FromRobotLog || B.FromRobotLog)
    return Notes;
  static const Series Absent;
  for (const auto &[SA, SB] : P.Values) {
    const llvm::json::Value &VA = (SA ? SA : &Absent)->at(Cycle);
    const llvm::json::Value &VB = (SB ? SB : &Absent)->at(Cycle);
    // A number compares as the float it is: a replay's values are the
    // floats themselves, a recording's the shortest decimals of them.
    if (debug::findDifference(VA, VB, ""))
      Notes.push_back((SA ? SA : SB)->Path + ": A " + describeValue(VA) +
                      ", B " + describeValue(VB));
  }
  return Notes;
}
} // namespace

std::optional<Difference> timeline::findFirstDifference(const Run &A,
                                                        const Run &B) {
  std::set<uint32_t> Cycles;
  addChangeCycles(A, Cycles);
  addChangeCycles(B, Cycles);
  Pairs P(A, B);
  for (uint32_t Cycle : Cycles) {
    bool InA = A.hasCycle(Cycle), InB = B.hasCycle(Cycle);
    if (InA != InB)
      return Difference{Cycle,
                        {std::string("cycle ") + std::to_string(Cycle) +
                         " is only in " + (InA ? "A" : "B")}};
    if (!InA)
      continue;
    std::vector<std::string> Notes = compareCycle(A, B, P, Cycle);
    if (!Notes.empty())
      return Difference{Cycle, std::move(Notes)};
  }
  return std::nullopt;
}

bool timeline::compareFiles(Compilation &C, llvm::ArrayRef<Run> A,
                            llvm::ArrayRef<Run> B,
                            std::optional<Difference> &Diff) {
  // One robot's run has Robot -1; a team's file has two runs or more, or
  // one of a team of one.
  auto RobotsOf = [](llvm::ArrayRef<Run> F) {
    return F.front().Robot < 0 ? 0 : F.size();
  };
  if (RobotsOf(A) != RobotsOf(B)) {
    auto Describe = [&](llvm::ArrayRef<Run> F) {
      return F.front().Robot < 0
                 ? "'" + F.front().Name + "' is one robot's run"
                 : "'" + F.front().Name + "' is a team of " +
                       std::to_string(F.size());
    };
    C.Diags.report(llvm::SMLoc(), diag::err_timeline_teams_differ)
        << Describe(A) << Describe(B);
    return false;
  }
  // The earliest cycle where any robot differs, with the notes of every
  // robot that differs in it.
  Diff.reset();
  for (size_t K = 0; K < A.size(); ++K) {
    std::optional<Difference> D = findFirstDifference(A[K], B[K]);
    if (!D || (Diff && Diff->Cycle < D->Cycle))
      continue;
    if (A[K].Robot >= 0)
      for (std::string &Note : D->Notes)
        Note = "robot " + std::to_string(K) + ": " + Note;
    if (Diff && Diff->Cycle == D->Cycle)
      llvm::append_range(Diff->Notes, D->Notes);
    else
      Diff = std::move(D);
  }
  return true;
}
