//===- Record.cpp - one cycle as a line of a recording -------------------===//
//
// `--record` and the REPL's `:record` write a header line, then a line per
// cycle: the inputs, the outputs, the active tasks with their fields and
// the calls into registered C++ with what they did (docs/repl.md,
// "Recordings"). The values go through bsc/Debug, so a recording and a
// decoded robot log spell them alike; the calls' bytes are hex, as the
// behavior's memory held them.
//
//===----------------------------------------------------------------------===//
#include "bsc/Run/Run.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/Support/ConvertUTF.h"

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

static std::string toHex(llvm::ArrayRef<unsigned char> Bytes) {
  return llvm::toHex(Bytes, /*LowerCase=*/true);
}

/// The calls of the cycle as recordings keep them: per call its function,
/// its result (hex, or `text` for a string), the bytes of the arguments it
/// may write (`args`) and the runs of the state, input and output it
/// changed (`writes`: [block, offset, hex]).
static llvm::json::Array recordCalls(const BehaviorSession &S) {
  size_t Sizes[3];
  S.getViewSizes(Sizes);
  llvm::json::Array Calls;
  for (const RecordedCall &C : decodeCalls(S.getLastCalls(), Sizes)) {
    llvm::json::Object Call{{"fn", C.Name}};
    llvm::StringRef Text(reinterpret_cast<const char *>(C.Result.data()),
                         C.Result.size());
    if (C.ResultIsString && llvm::json::isUTF8(Text)) {
      Call["text"] = Text.str();
    } else if (C.ResultIsString) {
      Call["string"] = toHex(C.Result);
    } else if (!C.Result.empty()) {
      Call["result"] = toHex(C.Result);
    }
    if (!C.Ptrs.empty()) {
      llvm::json::Array Args;
      for (const std::vector<unsigned char> &P : C.Ptrs)
        Args.push_back(toHex(P));
      Call["args"] = std::move(Args);
    }
    if (!C.Writes.empty()) {
      llvm::json::Array Writes;
      for (const RecordedCall::Write &W : C.Writes)
        Writes.push_back(llvm::json::Array{BoundaryBlockNames[W.Block],
                                           int64_t(W.Offset),
                                           toHex(W.Bytes)});
      Call["writes"] = std::move(Writes);
    }
    Calls.push_back(std::move(Call));
  }
  return Calls;
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
  if (Calls && S.getLastCalls().NumCalls)
    Rec["calls"] = recordCalls(S);
  return Rec;
}

/// Bytes from hex text; false if it is not.
static bool fromHex(llvm::StringRef Hex, std::vector<unsigned char> &Into) {
  std::string Bytes;
  if (Hex.size() % 2 || !llvm::tryGetFromHex(Hex, Bytes))
    return false;
  Into.assign(Bytes.begin(), Bytes.end());
  return true;
}

bool bsc::parseRecordedCalls(const llvm::json::Value &Value,
                             const BehaviorSession &S, CycleRecord &Into,
                             std::string &Error) {
  size_t Sizes[3];
  S.getViewSizes(Sizes);
  const llvm::json::Array *Array = Value.getAsArray();
  if (!Array) {
    Error = "'calls' must be an array of calls";
    return false;
  }
  std::vector<RecordedCall> Calls;
  for (const llvm::json::Value &V : *Array) {
    std::string Where = "call " + std::to_string(Calls.size() + 1);
    const llvm::json::Object *O = V.getAsObject();
    std::optional<llvm::StringRef> Fn = O ? O->getString("fn") : std::nullopt;
    if (!Fn) {
      Error = Where + " must be an object with the function's name in 'fn'";
      return false;
    }
    RecordedCall C;
    C.Name = Fn->str();
    Where += " ('" + C.Name + "')";
    for (const auto &[Key, Member] : *O) {
      std::optional<llvm::StringRef> Hex = Member.getAsString();
      if (Key == "fn") {
        continue;
      } else if (Key == "text" && Hex) {
        C.ResultIsString = true;
        C.Result.assign(Hex->begin(), Hex->end());
      } else if ((Key == "result" || Key == "string") && Hex &&
                 fromHex(*Hex, C.Result)) {
        C.ResultIsString = Key == "string";
      } else if (Key == "args" && Member.getAsArray()) {
        for (const llvm::json::Value &A : *Member.getAsArray()) {
          C.Ptrs.emplace_back();
          std::optional<llvm::StringRef> H = A.getAsString();
          if (!H || !fromHex(*H, C.Ptrs.back())) {
            Error = Where + ": 'args' must hold hex strings";
            return false;
          }
        }
      } else if (Key == "writes" && Member.getAsArray()) {
        for (const llvm::json::Value &W : *Member.getAsArray()) {
          const llvm::json::Array *Triple = W.getAsArray();
          std::optional<llvm::StringRef> Block =
              Triple && Triple->size() == 3 ? (*Triple)[0].getAsString()
                                            : std::nullopt;
          std::optional<int64_t> Offset =
              Block ? (*Triple)[1].getAsInteger() : std::nullopt;
          std::optional<llvm::StringRef> Bytes =
              Offset ? (*Triple)[2].getAsString() : std::nullopt;
          RecordedCall::Write Write{3, 0, {}};
          for (unsigned B = 0; Block && B < 3; ++B)
            if (*Block == BoundaryBlockNames[B])
              Write.Block = B;
          if (!Bytes || Write.Block > 2 || *Offset < 0 ||
              !fromHex(*Bytes, Write.Bytes)) {
            Error = Where + ": each of 'writes' must be [\"state\", \"input\" "
                            "or \"output\", an offset, hex bytes]";
            return false;
          }
          Write.Offset = uint64_t(*Offset);
          C.Writes.push_back(std::move(Write));
        }
      } else {
        Error = Where + ": unknown or malformed member '" + Key.str() +
                "'; a call has 'fn', 'result' or 'text', 'args' and "
                "'writes'";
        return false;
      }
    }
    Calls.push_back(std::move(C));
  }
  if (!encodeCalls(Calls, Sizes, Into, Error))
    return false;
  return true;
}
