//===- BinaryLogFuzzer.cpp - bytes into the reader of binary logs ----------===//
//
// libFuzzer target (`./dev.sh fuzz binlog`), and the same function run on a
// corpus by the replay driver in the test suite (fuzz/README.md). The input
// is a binary log (docs/repl.md, "The robot's log") as `bsc run --replay`,
// `bsc replay`, `bsc timeline` and `bsc convert` read it, a cycle at a
// time, with its calls translated into a view of another state size (the
// workstation's, larger than a robot's).
//
// What must hold, beyond not crashing or allocating without bound: a log
// the reader refuses says so with an error that names a byte; each cycle
// it gives has the header's sizes; and the cycles it read, written again
// by bsc's writer (raw and compressed), read back the same, call for call
// and byte for byte. A violation aborts, which both drivers report.
//
//===----------------------------------------------------------------------===//
#include "bsc/JIT/Boundary.h"
#include "bsc/Run/BinaryLog.h"
#include "llvm/Support/raw_ostream.h"
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

using namespace bsc;

namespace {
/// What a reader gave of one cycle, copied (its arrays live until the next).
struct Cycle {
  unsigned Robot;
  uint32_t Number;
  std::vector<unsigned char> Input, EntryOutput, Output, Calls, Trace;
  unsigned NumCalls;
  bool operator==(const Cycle &O) const {
    return Robot == O.Robot && Number == O.Number && Input == O.Input &&
           EntryOutput == O.EntryOutput && Output == O.Output &&
           Calls == O.Calls && Trace == O.Trace && NumCalls == O.NumCalls;
  }
};

constexpr uint64_t WorkstationState = 64;

/// Reads every cycle of `Bytes`; false if the reader refused it.
bool readAll(llvm::StringRef Bytes, BinaryLogHeader &Header,
             std::vector<Cycle> &Cycles) {
  BinaryLogReader R;
  if (!R.open(Bytes)) {
    if (R.getError().find("byte ") != 0)
      abort(); // An error names where it is.
    return false;
  }
  Header = R.getHeader();
  R.setView(WorkstationState);
  BinaryLogCycle C;
  while (R.next(C)) {
    if (C.Input.size() != Header.InputSize ||
        C.EntryOutput.size() != Header.OutputSize ||
        C.Output.size() != Header.OutputSize || C.Robot >= Header.Robots)
      abort();
    Cycles.push_back({C.Robot, C.Cycle,
                      {C.Input.begin(), C.Input.end()},
                      {C.EntryOutput.begin(), C.EntryOutput.end()},
                      {C.Output.begin(), C.Output.end()},
                      C.Calls,
                      {C.Trace.begin(), C.Trace.end()},
                      C.NumCalls});
  }
  if (R.failed() && R.getError().find("byte ") != 0)
    abort();
  return !R.failed();
}

/// `Cycles` written by bsc's writer (with the header's sites, whose ids
/// the reader's calls use) and read back: the same cycles.
void roundTrip(const BinaryLogHeader &Header, const std::vector<Cycle> &Cycles,
               bool Compress) {
  BinaryLogHeader H = Header;
  H.StateSize = WorkstationState; // The calls are in that view now.
  std::string Bytes;
  {
    llvm::raw_string_ostream OS(Bytes);
    BinaryLogWriter W(OS, H, Compress);
    for (const Cycle &C : Cycles) {
      CycleRecord Calls;
      Calls.Calls = C.Calls;
      Calls.NumCalls = C.NumCalls;
      W.writeCycle(C.Robot, C.Number, C.Input, C.EntryOutput, Calls, C.Output,
                   C.Trace);
    }
    W.finish();
  }
  BinaryLogHeader Again;
  std::vector<Cycle> Read;
  if (!readAll(Bytes, Again, Read) || Read.size() != Cycles.size())
    abort();
  for (size_t I = 0; I < Read.size(); ++I)
    if (!(Read[I] == Cycles[I]))
      abort();
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *Data, size_t Size) {
  llvm::StringRef Bytes(reinterpret_cast<const char *>(Data), Size);
  BinaryLogHeader Header;
  std::vector<Cycle> Cycles;
  readAll(Bytes, Header, Cycles);
  // A log the reader took, whole or up to its damage: written again.
  if (!Header.Entry.empty() || !Cycles.empty()) {
    roundTrip(Header, Cycles, /*Compress=*/false);
    roundTrip(Header, Cycles, /*Compress=*/true);
  }
  return 0;
}
