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
#include "llvm/TargetParser/Host.h"
#include "llvm/TargetParser/Triple.h"

using namespace bsc;

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
    for (const BehaviorLayout::FrameField &Field :
         L.Layout.Tasks[F.Record.Task].Fields) {
      bool IsParam = llvm::isa<ParamDecl>(Field.D);
      // A finished task's locals are gone (the next call starts afresh).
      if (!IsParam && F.Record.Resume == 0)
        continue;
      llvm::json::Object &Into = IsParam ? Params : Locals;
      // Locals of one name in different blocks: `x`, `x#2`, ... in the
      // frame's order.
      std::string Name = Field.D->getName().Name.str();
      for (unsigned N = 2; Into.find(Name) != Into.end(); ++N)
        Name = Field.D->getName().Name.str() + "#" + std::to_string(N);
      Into[Name] = Values.read(Field.Ty, State + Field.Offset);
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
