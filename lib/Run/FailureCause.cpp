//===- FailureCause.cpp - which task a failed replay went astray in -------===//
#include "FailureCause.h"
#include "llvm/ADT/StringMap.h"
#include "llvm/ADT/StringSet.h"

using namespace bsc;

/// The hierarchy of a cycle's activations (a snapshot of the state, or a
/// robot's trace record), named.
static std::vector<ActiveTaskView>
viewTasks(const LoadedBehavior &L, llvm::ArrayRef<debug::Activation> Records) {
  std::vector<debug::RecordedTask> Listed =
      debug::listActiveTasks(L.Tables, Records);
  std::vector<ActiveTaskView> Tasks;
  for (const debug::RecordedTask &T : Listed)
    Tasks.push_back(
        {L.Tables.Tasks[T.Record.Task].Name, T.State, T.Place,
         T.Parent < 0 ? "" : L.Tables.Tasks[Listed[T.Parent].Record.Task].Name});
  return Tasks;
}

std::optional<std::vector<ActiveTaskView>>
bsc::recordedTasks(const LoadedBehavior &L, const ReplayLine &Line) {
  if (Line.Logged) {
    if (Line.Logged->Trace.empty())
      return std::nullopt;
    llvm::Expected<std::vector<debug::Activation>> Records =
        debug::decodeTraceRecord(L.Tables, Line.Logged->Trace);
    if (!Records) {
      llvm::consumeError(Records.takeError()); // The replay reports it.
      return std::nullopt;
    }
    return viewTasks(L, *Records);
  }
  if (Line.Tasks.empty())
    return std::nullopt;
  return parseRecordedTasks(Line.Tasks);
}

std::optional<std::vector<ActiveTaskView>>
bsc::parseRecordedTasks(llvm::StringRef Text) {
  llvm::Expected<llvm::json::Value> V = llvm::json::parse(Text);
  if (!V) {
    llvm::consumeError(V.takeError());
    return std::nullopt;
  }
  const llvm::json::Array *A = V->getAsArray();
  if (!A)
    return std::nullopt;
  std::vector<ActiveTaskView> Tasks;
  llvm::StringSet<> Names; // A task is active once in a cycle.
  for (const llvm::json::Value &E : *A) {
    const llvm::json::Object *O = E.getAsObject();
    std::optional<llvm::StringRef> Name =
        O ? O->getString("task") : std::nullopt;
    std::optional<llvm::StringRef> State =
        O ? O->getString("state") : std::nullopt;
    std::optional<int64_t> Parent = O ? O->getInteger("parent") : std::nullopt;
    if (!Name || !State || !Parent || *Parent < -1 ||
        *Parent >= int64_t(Tasks.size()) || !Names.insert(*Name).second)
      return std::nullopt;
    Tasks.push_back({Name->str(), State->str(),
                     O->getString("at").value_or("").str(),
                     *Parent < 0 ? "" : Tasks[*Parent].Name});
  }
  return Tasks;
}

std::vector<ActiveTaskView> bsc::replayedTasks(const LoadedBehavior &L,
                                               const BehaviorSession &S) {
  return viewTasks(L, debug::takeSnapshot(S.getState(), &S.getInfo()));
}

/// `running at Kick.bs:10 under Kick::main`, or `not active`.
static std::string describe(const ActiveTaskView *T) {
  if (!T)
    return "not active";
  std::string Text = T->State;
  if (!T->Place.empty())
    Text += " at " + T->Place;
  if (!T->Parent.empty())
    Text += " under " + T->Parent;
  return Text;
}

std::optional<TaskDifference>
bsc::findTaskDifference(llvm::ArrayRef<ActiveTaskView> Recorded,
                        llvm::ArrayRef<ActiveTaskView> Replayed) {
  llvm::StringMap<const ActiveTaskView *> InReplay, InRecording;
  for (const ActiveTaskView &T : Replayed)
    InReplay.try_emplace(T.Name, &T);
  for (const ActiveTaskView &T : Recorded)
    InRecording.try_emplace(T.Name, &T);
  auto Differ = [](const ActiveTaskView &A, const ActiveTaskView &B) {
    return A.State != B.State || A.Place != B.Place || A.Parent != B.Parent;
  };
  for (const ActiveTaskView &R : Recorded) {
    const ActiveTaskView *G = InReplay.lookup(R.Name);
    if (G && !Differ(R, *G))
      continue;
    // Whether a task runs, and under whom, its caller decides.
    std::string Explains = !G ? R.Parent
                           : R.Parent != G->Parent ? G->Parent
                                                   : R.Name;
    return TaskDifference{R.Name, describe(&R), describe(G), Explains};
  }
  for (const ActiveTaskView &G : Replayed)
    if (!InRecording.count(G.Name))
      return TaskDifference{G.Name, describe(nullptr), describe(&G), G.Parent};
  return std::nullopt;
}
