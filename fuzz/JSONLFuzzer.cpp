//===- JSONLFuzzer.cpp - bytes into the reader of recordings ---------------===//
//
// libFuzzer target (`./dev.sh fuzz jsonl`), and the same function run on a
// corpus by the replay driver in the test suite (fuzz/README.md). The input
// is a recording as `bsc run --replay` and the REPL's `:replay` read it:
// one JSON value per line, through bsc::parseJSON (the one entry point for
// JSON), and each line's `input` and `output` written into an object of a
// made-up world class with a member of every kind a binding can register.
// The replay itself needs a JIT and a binding object, so this target takes
// the path it shares with them: parsing, and ValueIO writing and reading.
//
// What must hold, beyond not crashing: an error points into its line, an
// object read back and written again reads back the same (a recording
// replays bit for bit), and bsc::isJSON agrees with the parser. A line's
// `calls` (bsc/JIT/Boundary.h) that are accepted spell the same calls
// when written again, and a replay of them (as bytes, and the line's own
// bytes taken as an encoded record) into a made-up behavior's memory stays
// inside it. A line's `tasks`, as a failed replay's second look reads
// them (lib/Run/FailureCause.h), name their parents before them. A
// violation aborts, which both drivers report.
//
//===----------------------------------------------------------------------===//
#include "FailureCause.h"
#include "bsc/AST/Native.h"
#include "bsc/Basic/JSON.h"
#include "bsc/Debug/Values.h"
#include "bsc/JIT/Boundary.h"
#include "llvm/ADT/SmallVector.h"
#include <cstddef>
#include <cstdint>
#include <cstdlib>

using namespace bsc;

namespace {
struct Vec {
  float X, Y;
};
/// The made-up world's input and output: what a registered class holds.
struct World {
  int32_t Time;
  uint8_t Small; ///< Zero-extended when read.
  bool Flag;
  float F;
  double D; ///< A b-script float kept in 8 bytes.
  const char *Name;
  int32_t Motion; ///< The enum.
  Vec Pos;
  int16_t Grid[2][3];
};

void addField(NativeClass &C, const char *Name, NativeType::Code Code,
              uint64_t Offset, uint32_t Size, bool Unsigned = false,
              std::vector<uint32_t> Extents = {}) {
  NativeFunction F;
  F.Kind = NativeFunction::Field;
  F.Name = Name;
  F.FieldOffset = Offset;
  F.Result.TheCode = Code;
  F.Result.StorageSize = Size;
  F.Result.Unsigned = Unsigned;
  F.Result.Extents = std::move(Extents);
  C.Members.push_back(std::move(F));
}

/// The classes, built once: the target runs millions of times.
struct Model {
  NativeEnum Motion;
  NativeClass VecClass, WorldClass;

  Model() {
    Motion.Name = "MotionType";
    Motion.Values = {{"stand", 0}, {"walk", 1}, {"kick", 2}};
    VecClass.Name = "Vec";
    VecClass.QualifiedName = "World::Vec";
    addField(VecClass, "x", NativeType::Float, offsetof(Vec, X), 4);
    addField(VecClass, "y", NativeType::Float, offsetof(Vec, Y), 4);
    WorldClass.Name = "Input";
    WorldClass.QualifiedName = "World::Input";
    addField(WorldClass, "time", NativeType::Int, offsetof(World, Time), 4);
    addField(WorldClass, "small", NativeType::Int, offsetof(World, Small), 1,
             /*Unsigned=*/true);
    addField(WorldClass, "flag", NativeType::Bool, offsetof(World, Flag), 1);
    addField(WorldClass, "f", NativeType::Float, offsetof(World, F), 4);
    addField(WorldClass, "d", NativeType::Float, offsetof(World, D), 8);
    addField(WorldClass, "name", NativeType::String, offsetof(World, Name),
             sizeof(const char *));
    addField(WorldClass, "motion", NativeType::Enum, offsetof(World, Motion), 4);
    WorldClass.Members.back().Result.TheEnum = &Motion;
    addField(WorldClass, "pos", NativeType::Class, offsetof(World, Pos),
             sizeof(Vec));
    WorldClass.Members.back().Result.TheClass = &VecClass;
    addField(WorldClass, "grid", NativeType::Int, offsetof(World, Grid), 2,
             false, {2, 3});
  }
};

/// An error must point into the text it is about, at the line and column
/// of its offset.
void checkError(llvm::StringRef Line, const JSONReadError &E) {
  if (E.Offset > Line.size() || E.Message.empty())
    std::abort();
  llvm::StringRef Before = Line.take_front(E.Offset);
  size_t LineStart = Before.rfind('\n') + 1; // npos + 1 is 0
  if (E.Line != 1 + Before.count('\n') || E.Column != E.Offset - LineStart + 1)
    std::abort();
}

/// Writes `V` into `Obj` as a replay writes a line's member; when it is
/// accepted, what reads back must read back the same after a second write.
void replayMember(debug::ValueIO &IO, const NativeClass &C, World &Obj,
                  const llvm::json::Value &V) {
  if (llvm::Error E = IO.writeClass(C, &Obj, V, "input")) {
    llvm::consumeError(std::move(E));
    return;
  }
  llvm::json::Value First = IO.readClass(C, &Obj);
  if (llvm::Error E = IO.writeClass(C, &Obj, First, "input"))
    std::abort(); // What bsc records, it must replay.
  llvm::json::Value Second = IO.readClass(C, &Obj);
  if (debug::findDifference(First, Second, "input"))
    std::abort();
  (void)debug::toJSONString(Second);
}
} // namespace

/// A record replayed into a made-up view through a site of each shape the
/// wrappers have: no call may write outside the view, its result slot or
/// its pointer argument (ASan sees it), whatever the record holds.
void replayRecord(const CycleRecord &R) {
  static unsigned char State[64], Input[sizeof(World)], Output[sizeof(World)];
  Boundary B(State, sizeof State, Input, sizeof Input, Output, sizeof Output);
  static const uint32_t PtrSizes[] = {8};
  static const bs_boundary_site Sites[] = {
      {"f", 0, 4, 0, nullptr, 0},
      {"g", SiteResultIsString, sizeof(char *), 1, PtrSizes, 1},
      {"h", 0, 0, 1, PtrSizes, 2}};
  B.startReplay(R);
  uint64_t Result = 0;
  unsigned char Arg[8];
  void *Ptrs[] = {Arg};
  for (unsigned I = 0; I < R.NumCalls + 2; ++I) {
    const bs_boundary_site &S = Sites[I % 3];
    B.enter(&S);
    B.leave(&S, S.result_size ? &Result : nullptr,
            S.num_ptrs ? Ptrs : nullptr);
  }
  B.finish();
}

/// A line's `calls`: if accepted, written again they read the same.
void checkCalls(const llvm::json::Value &Calls) {
  static const size_t Sizes[3] = {64, sizeof(World), sizeof(World)};
  CycleRecord R;
  std::string Error;
  if (!callsFromJSON(Calls, Sizes, R, Error))
    return;
  CycleRecord Again;
  if (!callsFromJSON(callsToJSON(R, Sizes), Sizes, Again, Error) ||
      Again.Calls != R.Calls || Again.NumCalls != R.NumCalls)
    std::abort();
  replayRecord(R);
}

namespace {
/// A line's `tasks`, as a failed replay's second look reads them: taken,
/// each parent is an earlier task, and the tasks do not differ from
/// themselves.
void checkTasks(const llvm::json::Value &Tasks) {
  std::optional<std::vector<ActiveTaskView>> Read =
      parseRecordedTasks(debug::toJSONString(Tasks));
  if (!Read)
    return;
  for (size_t I = 0; I < Read->size(); ++I)
    if (!(*Read)[I].Parent.empty() &&
        llvm::none_of(llvm::ArrayRef(*Read).take_front(I),
                      [&](const ActiveTaskView &T) {
                        return T.Name == (*Read)[I].Parent;
                      }))
      std::abort();
  if (findTaskDifference(*Read, *Read))
    std::abort();
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *Data, size_t Size) {
  static const Model M;
  llvm::StringRef Text(reinterpret_cast<const char *>(Data), Size);
  debug::ValueIO IO([](llvm::StringRef) -> void * { return nullptr; });
  World Obj = {};
  // The bytes themselves as an encoded record: its reader must not trust
  // them either.
  CycleRecord Raw;
  Raw.Calls.assign(Data, Data + Size);
  Raw.NumCalls = unsigned(Size % 7);
  replayRecord(Raw);
  llvm::SmallVector<llvm::StringRef, 0> Lines;
  Text.split(Lines, '\n');
  for (llvm::StringRef Line : Lines) {
    llvm::Expected<llvm::json::Value> V = parseJSON(Line);
    // The replay's check of the parts of a line it skips must accept
    // exactly what the parser accepts.
    if (isJSON(Line) != bool(V))
      std::abort();
    if (!V) {
      llvm::handleAllErrors(V.takeError(), [&](const JSONReadError &E) {
        checkError(Line, E);
      });
      continue;
    }
    const llvm::json::Object *O = V->getAsObject();
    if (!O)
      continue;
    if (const llvm::json::Value *Calls = O->get("calls"))
      checkCalls(*Calls);
    if (const llvm::json::Value *Tasks = O->get("tasks"))
      checkTasks(*Tasks);
    for (llvm::StringRef Key : {"input", "output"})
      if (const llvm::json::Value *Member = O->get(Key))
        replayMember(IO, M.WorldClass, Obj, *Member);
  }
  return 0;
}
