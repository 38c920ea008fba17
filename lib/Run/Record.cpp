//===- Record.cpp - one cycle as a line of a recording -------------------===//
//
// `--record` and the REPL's `:record` write a header line, then a line per
// cycle: the inputs, the outputs, the active tasks with their fields and
// the calls into registered C++ with what they did (docs/repl.md,
// "Recordings"). The values go through bsc/Debug, so a recording and a
// decoded robot log spell them alike; the calls are spelled by
// bsc/JIT/Boundary.h (callsToJSON).
//
//===----------------------------------------------------------------------===//
#include "bsc/Run/Run.h"
#include "bsc/Timeline/Timeline.h"
#include "llvm/ADT/StringSet.h"
#include <cstring>
#include "llvm/TargetParser/Host.h"
#include "llvm/TargetParser/Triple.h"

using namespace bsc;

std::vector<std::string>
bsc::recordedFieldNames(const BehaviorLayout::Task &T) {
  std::vector<std::string> Names;
  llvm::StringSet<> Params, Locals;
  for (const BehaviorLayout::FrameField &Field : T.Fields) {
    llvm::StringSet<> &Taken = llvm::isa<ParamDecl>(Field.D) ? Params : Locals;
    llvm::StringRef Base = Field.D->getName().Name;
    std::string Name = Base.str();
    for (unsigned N = 2; !Taken.insert(Name).second; ++N)
      Name = Base.str() + "#" + std::to_string(N);
    Names.push_back(std::move(Name));
  }
  return Names;
}

/// The cycle's hierarchy as a recording keeps it: depth first, each task
/// with its state, the yield it waits at, its parent's position and its
/// parameters and (unless it finished) locals.
static llvm::json::Array recordTasks(debug::ValueIO &Values,
                                     const LoadedBehavior &L,
                                     const BehaviorSession &S) {
  const auto *State = static_cast<const char *>(S.getState());
  llvm::json::Array Tasks;
  for (const debug::RecordedTask &F : debug::listActiveTasks(
           L.Tables, debug::takeSnapshot(State, &S.getInfo()))) {
    llvm::json::Object Task{{"task", L.Tables.Tasks[F.Record.Task].Name},
                            {"state", F.State},
                            {"parent", F.Parent}};
    if (!F.Place.empty())
      Task["at"] = F.Place;
    llvm::json::Object Params, Locals;
    const BehaviorLayout::Task &Layout = L.Layout.Tasks[F.Record.Task];
    std::vector<std::string> Names = recordedFieldNames(Layout);
    for (size_t I = 0; I < Layout.Fields.size(); ++I) {
      const BehaviorLayout::FrameField &Field = Layout.Fields[I];
      bool IsParam = llvm::isa<ParamDecl>(Field.D);
      // A finished task's locals are gone (the next call starts afresh).
      if (!IsParam && F.Record.Resume == 0)
        continue;
      (IsParam ? Params : Locals)[Names[I]] =
          Values.read(Field.Ty, State + Field.Offset);
    }
    if (!Params.empty())
      Task["params"] = std::move(Params);
    if (!Locals.empty())
      Task["locals"] = std::move(Locals);
    Tasks.push_back(std::move(Task));
  }
  return Tasks;
}

llvm::json::Value bsc::recordHeader(const LoadedBehavior &L) {
  return llvm::json::Object{
      {"recording",
       llvm::json::Object{{"format", int64_t(RecordingFormat)},
                          {"behavior", L.Hash},
                          {"entry", L.Entry->getQualifiedName()}}}};
}

llvm::json::Value bsc::recordCycle(debug::ValueIO &Values,
                                   const LoadedBehavior &L,
                                   const BehaviorSession &S) {
  llvm::json::Object Rec{{"cycle", int64_t(S.getCycle())}};
  bool Calls = S.keepsCalls();
  const std::vector<unsigned char> &Entry = S.getLastCalls().EntryInput;
  if (L.InputClass)
    Rec["input"] = Values.readClass(
        *L.InputClass,
        Calls && Entry.size() == L.Input.Size ? Entry.data() : S.getInput());
  if (L.OutputClass)
    Rec["output"] = Values.readClass(*L.OutputClass, S.getOutput());
  Rec["tasks"] = recordTasks(Values, L, S);
  // A cycle that called no C++ (or only pure C++) has no `calls`.
  if (Calls && S.getLastCalls().NumCalls) {
    size_t Sizes[3];
    S.getViewSizes(Sizes);
    Rec["calls"] = callsToJSON(S.getLastCalls(), Sizes);
  }
  return Rec;
}

TimelineFeed::TimelineFeed(const LoadedBehavior &L, timeline::CycleSink &Sink)
    : L(L), Sink(Sink),
      Values([&L](llvm::StringRef Sym) { return L.JIT->lookup(Sym); }),
      Lister(L.Tables), Tasks(L.Layout.Tasks.size()) {
  Input.Class = L.InputClass;
  Input.Name = "input";
  Output.Class = L.OutputClass;
  Output.Name = "output";
}

/// The bytes a frame field of type `T` reads from, as ValueIO::read reads
/// them; 0 if its value is more than they are (a string's pointer, whose
/// text may change; a class that does not copy as bytes).
static unsigned bytesOfValue(const Type *T) {
  switch (T->getKind()) {
  case TypeKind::Int:
  case TypeKind::TaskState:
  case TypeKind::Enum:
  case TypeKind::Float:
    return 4;
  case TypeKind::Bool:
    return 1;
  case TypeKind::Class:
    return T->getClass()->CopiesAsBytes ? T->getClass()->Size : 0;
  case TypeKind::String:
  case TypeKind::Error:
  case TypeKind::Void:
  case TypeKind::Array:
    return 0;
  }
  return 0;
}

void TimelineFeed::takeObject(WorldObject &O, const void *Bytes,
                              size_t Size) {
  if (!O.Class)
    return;
  auto *Begin = static_cast<const unsigned char *>(Bytes);
  if (Generation > 1 && O.Class->CopiesAsBytes && O.Bytes.size() == Size &&
      std::equal(Begin, Begin + Size, O.Bytes.begin())) {
    for (unsigned Leaf : O.Leaves)
      Sink.keepValue(Leaf);
    return;
  }
  // Each leaf a value of its own, so that none of the objects readClass
  // would build is built.
  std::string Path = O.Name;
  size_t K = 0;
  Values.readLeaves(*O.Class, Bytes, Path,
                    [&](llvm::StringRef Leaf, const llvm::json::Value &V) {
                      if (K == O.Leaves.size()) {
                        O.Paths.push_back(Leaf.str());
                        O.Leaves.push_back(Sink.valueIndex(Leaf));
                      } else if (O.Paths[K] != Leaf) {
                        O.Paths[K] = Leaf.str();
                        O.Leaves[K] = Sink.valueIndex(Leaf);
                      }
                      Sink.setValue(O.Leaves[K++], V);
                    });
  O.Paths.resize(K);
  O.Leaves.resize(K);
  O.Bytes.assign(Begin, Begin + Size);
}

void TimelineFeed::takeTask(TaskFeed &T, unsigned Task, const char *State,
                            bool Finished) {
  const BehaviorLayout::Task &Layout = L.Layout.Tasks[Task];
  if (T.Fields.size() != Layout.Fields.size()) {
    std::vector<std::string> Names = recordedFieldNames(Layout);
    for (size_t I = 0; I < Layout.Fields.size(); ++I) {
      T.Fields.push_back(Sink.fieldIndex(
          T.Lane, Names[I], llvm::isa<ParamDecl>(Layout.Fields[I].D)));
      T.Bytes.push_back(bytesOfValue(Layout.Fields[I].Ty));
    }
  }
  // A field keeps its value if the task was active in the cycle before,
  // as finished or not, and the field's bytes in the frame are the same.
  const char *Frame = State + Layout.FrameOffset;
  bool Before = T.ActiveIn + 1 == Generation && T.Finished == Finished &&
                T.Frame.size() == Layout.FrameSize;
  for (size_t I = 0; I < Layout.Fields.size(); ++I) {
    const BehaviorLayout::FrameField &Field = Layout.Fields[I];
    // A finished task's locals are gone (the next call starts afresh).
    if (Finished && !llvm::isa<ParamDecl>(Field.D))
      continue;
    uint64_t At = Field.Offset - Layout.FrameOffset;
    if (Before && T.Bytes[I] &&
        std::memcmp(Frame + At, T.Frame.data() + At, T.Bytes[I]) == 0)
      Sink.keepValue(T.Fields[I]);
    else
      Sink.setValue(T.Fields[I], Values.read(Field.Ty, State + Field.Offset));
  }
  T.Frame.assign(Frame, Frame + Layout.FrameSize);
  T.ActiveIn = Generation;
  T.Finished = Finished;
}

void TimelineFeed::take(const BehaviorSession &S) {
  ++Generation;
  Sink.beginCycle(S.getCycle());
  // The input the entry saw, as recordCycle writes it.
  const std::vector<unsigned char> &Entry = S.getLastCalls().EntryInput;
  takeObject(Input,
             S.keepsCalls() && Entry.size() == L.Input.Size ? Entry.data()
                                                            : S.getInput(),
             L.Input.Size);
  takeObject(Output, S.getOutput(), L.Output.Size);

  const auto *State = static_cast<const char *>(S.getState());
  std::vector<int> LaneAt; // Of each listed task, for its children.
  for (const debug::RecordedTask &F :
       Lister.list(debug::takeSnapshot(State, &S.getInfo()))) {
    TaskFeed &T = Tasks[F.Record.Task];
    if (T.Lane < 0)
      T.Lane = Sink.laneIndex(L.Tables.Tasks[F.Record.Task].Name);
    LaneAt.push_back(T.Lane);
    Sink.addTask(T.Lane, F.State, F.Place, F.Parent < 0 ? -1 : LaneAt[F.Parent]);
    takeTask(T, F.Record.Task, State, F.Record.Resume == 0);
  }
  Sink.endCycle();
}

bool bsc::isBinaryLogPath(llvm::StringRef Path) {
  return Path.ends_with(".bslog");
}

bool bsc::checkWorldAsBytes(DiagnosticEngine &Diags, llvm::SMLoc Loc,
                            const LoadedBehavior &L, llvm::StringRef Path) {
  for (const NativeClass *C : {L.InputClass, L.OutputClass})
    if (C && !C->CopiesAsBytes && !C->TriviallyDestructible) {
      Diags.report(Loc, diag::err_log_not_bytes) << Path << C->QualifiedName;
      return false;
    }
  return true;
}

BinaryLogHeader bsc::logHeader(const Compilation &C, const LoadedBehavior &L,
                               const BehaviorSession &S, unsigned Robots) {
  BinaryLogHeader H;
  H.Behavior = L.Hash;
  H.Entry = L.Entry->getQualifiedName();
  H.Target = llvm::Triple(llvm::sys::getProcessTriple()).getArchName().str();
  H.Layout = getIOLayoutHash(C.Checked);
  size_t Sizes[3];
  S.getViewSizes(Sizes);
  H.StateSize = Sizes[0];
  H.InputSize = Sizes[1];
  H.OutputSize = Sizes[2];
  H.Robots = Robots;
  return H;
}

void bsc::logCycle(BinaryLogWriter &Log, unsigned Robot,
                   const LoadedBehavior &L, const BehaviorSession &S) {
  auto Bytes = [](const void *P, size_t N) {
    return llvm::ArrayRef<unsigned char>(static_cast<const unsigned char *>(P),
                                         P ? N : 0);
  };
  llvm::ArrayRef<unsigned char> Input = Bytes(S.getInput(), L.Input.Size);
  const CycleRecord &Calls = S.getLastCalls();
  llvm::ArrayRef<unsigned char> Entry =
      Calls.EntryInput.size() == Input.size()
          ? llvm::ArrayRef<unsigned char>(Calls.EntryInput)
          : Input;
  llvm::ArrayRef<unsigned char> Output = Bytes(S.getOutput(), L.Output.Size);
  llvm::ArrayRef<unsigned char> EntryOutput =
      Calls.EntryOutput.size() == Output.size()
          ? llvm::ArrayRef<unsigned char>(Calls.EntryOutput)
          : Output;
  Log.writeCycle(Robot, S.getCycle(), Entry, EntryOutput, Calls, Output);
}

bool bsc::parseRecordedCalls(const llvm::json::Value &Value,
                             const BehaviorSession &S, CycleRecord &Into,
                             std::string &Error) {
  size_t Sizes[3];
  S.getViewSizes(Sizes);
  return callsFromJSON(Value, Sizes, Into, Error);
}
