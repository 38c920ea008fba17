//===- Convert.cpp - bsc convert: a recording in the other format ----------===//
//
// A JSON-lines recording becomes a binary log and back, cycle by cycle,
// without running the behavior: what the file says is written in the
// other form, its header's behavior and entry included, so that a log of
// another behavior version still replays in regression mode after the
// round trip. The behavior is needed for the layout of `input` and
// `output` (bytes on one side, members on the other); a session of it
// lends its objects to turn the one into the other.
//
//===----------------------------------------------------------------------===//
#include "ReplayReader.h"
#include "bsc/Basic/JSON.h"
#include "bsc/Basic/Output.h"
#include "bsc/Run/Run.h"
#include "llvm/Support/ToolOutputFile.h"
#include <cstring>

using namespace bsc;

namespace {
/// Writes the cycles of one reader in the other format.
class Converter {
public:
  Converter(Compilation &C, LoadedBehavior &L, BehaviorSession &S)
      : C(C), L(L), S(S),
        Values([&L](llvm::StringRef Sym) { return L.JIT->lookup(Sym); }) {}

  bool run(llvm::StringRef From, llvm::StringRef To);

private:
  /// A JSON line's `input` or `output` text into `Obj`; false after
  /// reporting.
  bool writeText(const NativeClass &Class, void *Obj, llvm::StringRef Text,
                 llvm::SMLoc Loc, const char *What);
  bool toBinary(ReplayReader &R, llvm::raw_ostream &OS);
  bool toJSON(ReplayReader &R, llvm::raw_ostream &OS, llvm::StringRef From);

  Compilation &C;
  LoadedBehavior &L;
  BehaviorSession &S;
  debug::ValueIO Values;
};
} // namespace

bool Converter::writeText(const NativeClass &Class, void *Obj,
                          llvm::StringRef Text, llvm::SMLoc Loc,
                          const char *What) {
  if (Values.writeClassText(Class, Obj, Text))
    return true;
  std::optional<llvm::json::Value> V = parseJSONLine(C.Diags, Text);
  if (!V)
    return false;
  if (llvm::Error E = Values.writeClass(Class, Obj, *V, What)) {
    C.Diags.report(Loc, diag::err_replay_value) << llvm::toString(std::move(E));
    return false;
  }
  return true;
}

bool Converter::toBinary(ReplayReader &R, llvm::raw_ostream &OS) {
  unsigned Robots = R.countRobots();
  BinaryLogHeader H = logHeader(C, L, S, Robots);
  // The recording's own behavior and entry: the log replays as it would.
  H.Behavior = R.getHeader().Behavior;
  H.Entry = R.getHeader().Entry;
  BinaryLogWriter Log(OS, H, /*Compress=*/true);
  auto Bytes = [](void *P, size_t N) {
    return llvm::ArrayRef<unsigned char>(static_cast<unsigned char *>(P),
                                         P ? N : 0);
  };
  std::vector<uint32_t> Cycles(Robots, 0);
  // Each robot's objects as its last line left them (a line may leave a
  // member out), in the session's objects while a line is written.
  auto Snapshot = [&](void *P, size_t N) {
    auto B = Bytes(P, N);
    return std::vector<unsigned char>(B.begin(), B.end());
  };
  std::vector<std::vector<unsigned char>> Inputs(
      Robots, Snapshot(S.getInput(), L.Input.Size)),
      Outputs(Robots, Snapshot(S.getOutput(), L.Output.Size));
  ReplayLine Line;
  while (R.next(Line)) {
    unsigned Robot = Line.Robot.value_or(0);
    if (Robot >= Robots) {
      C.Diags.report(Line.Loc, diag::err_replay_value)
          << "a line of robot " + std::to_string(Robot) + " in a recording "
                 "of " + std::to_string(Robots);
      return false;
    }
    if (!Inputs[Robot].empty())
      std::memcpy(S.getInput(), Inputs[Robot].data(), Inputs[Robot].size());
    if (!Outputs[Robot].empty())
      std::memcpy(S.getOutput(), Outputs[Robot].data(), Outputs[Robot].size());
    // A JSON line's entry found the output the line before left.
    std::vector<unsigned char> EntryOutput = Outputs[Robot];
    if ((!Line.Input.empty() &&
         !writeText(*L.InputClass, S.getInput(), Line.Input, Line.Loc,
                    "input")) ||
        (!Line.Output.empty() &&
         !writeText(*L.OutputClass, S.getOutput(), Line.Output, Line.Loc,
                    "output")))
      return false;
    CycleRecord Calls;
    if (!Line.Calls.empty()) {
      std::optional<llvm::json::Value> V = parseJSONLine(C.Diags, Line.Calls);
      std::string Error;
      if (!V)
        return false;
      if (!parseRecordedCalls(*V, S, Calls, Error)) {
        C.Diags.report(Line.Loc, diag::err_replay_calls) << Error;
        return false;
      }
    }
    Inputs[Robot] = Snapshot(S.getInput(), L.Input.Size);
    Outputs[Robot] = Snapshot(S.getOutput(), L.Output.Size);
    Log.writeCycle(Robot, ++Cycles[Robot], Inputs[Robot], EntryOutput, Calls,
                   Outputs[Robot]);
  }
  Log.finish();
  return !R.failed();
}

bool Converter::toJSON(ReplayReader &R, llvm::raw_ostream &OS,
                       llvm::StringRef From) {
  const RecordingHeader &H = R.getHeader();
  debug::printJSON(
      OS, llvm::json::Object{
              {"recording", llvm::json::Object{{"format", int64_t(H.Format)},
                                               {"behavior", H.Behavior},
                                               {"entry", H.Entry}}}});
  OS << "\n";
  size_t Sizes[3];
  S.getViewSizes(Sizes);
  bool Team = R.countRobots() > 1;
  // The bytes, aligned for the classes' getters.
  std::vector<uint64_t> In((L.Input.Size + 7) / 8), Out((L.Output.Size + 7) / 8);
  // What each robot's next entry finds in JSON lines: the output the line
  // before left (the first: the session's new object).
  const auto *Fresh = static_cast<const unsigned char *>(S.getOutput());
  std::vector<std::vector<unsigned char>> Left(
      R.countRobots(), std::vector<unsigned char>(
                           Fresh, Fresh + (Fresh ? L.Output.Size : 0)));
  ReplayLine Line;
  while (R.next(Line)) {
    const BinaryLogCycle &Cycle = *Line.Logged;
    std::vector<unsigned char> &Before = Left[Cycle.Robot];
    if (!llvm::equal(Cycle.EntryOutput, Before)) {
      C.Diags.report(llvm::SMLoc(), diag::err_convert_entry_output)
          << From << Cycle.Cycle;
      return false;
    }
    Before.assign(Cycle.Output.begin(), Cycle.Output.end());
    llvm::json::Object Rec{{"cycle", int64_t(Cycle.Cycle)}};
    if (Team)
      Rec["robot"] = int64_t(Cycle.Robot);
    if (L.InputClass) {
      std::memcpy(In.data(), Cycle.Input.data(), Cycle.Input.size());
      Rec["input"] = Values.readClass(*L.InputClass, In.data());
    }
    if (L.OutputClass) {
      std::memcpy(Out.data(), Cycle.Output.data(), Cycle.Output.size());
      Rec["output"] = Values.readClass(*L.OutputClass, Out.data());
    }
    if (Cycle.NumCalls) {
      CycleRecord Calls;
      Calls.Calls = Cycle.Calls;
      Calls.NumCalls = Cycle.NumCalls;
      Rec["calls"] = callsToJSON(Calls, Sizes);
    }
    debug::printJSON(OS, std::move(Rec));
    OS << "\n";
  }
  return !R.failed();
}

bool Converter::run(llvm::StringRef From, llvm::StringRef To) {
  ReplayReader R(C, L);
  if (!R.open(From))
    return false;
  bool Binary = isBinaryLogPath(To);
  if (Binary == R.getHeader().Binary) {
    C.Diags.report(llvm::SMLoc(), diag::err_convert_same_format)
        << From << To << (Binary ? "binary log" : "JSON-lines recording");
    return false;
  }
  if (Binary && !checkWorldAsBytes(C.Diags, llvm::SMLoc(), L, To))
    return false;
  std::unique_ptr<llvm::ToolOutputFile> Out =
      openOutput(C.Diags, To, /*Text=*/!Binary);
  if (!Out)
    return false;
  if (!(Binary ? toBinary(R, Out->os()) : toJSON(R, Out->os(), From)))
    return false;
  Out->keep();
  return true;
}

bool bsc::convertRecording(Compilation &C, LoadedBehavior &L,
                           BehaviorSession &S, llvm::StringRef From,
                           llvm::StringRef To) {
  return Converter(C, L, S).run(From, To);
}
