//===- BinaryLogTest.cpp - the binary log's writer and reader ---------------===//
//
// Cycles written by BinaryLogWriter read back the same from
// BinaryLogReader: whole in key cycles and as changes in between, with
// calls in the process's site ids, names added as they come, a team's
// robots interleaved, raw and compressed; and the reader's errors name
// the byte and the cycle of what is wrong.
//
//===----------------------------------------------------------------------===//
#include "bsc/JIT/Boundary.h"
#include "bsc/Run/BinaryLog.h"
#include "bsc/Run/Run.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/raw_ostream.h"
#include "gtest/gtest.h"

using namespace bsc;

namespace {
using Bytes = std::vector<unsigned char>;

BinaryLogHeader header(unsigned Robots = 1) {
  BinaryLogHeader H;
  H.Behavior = "0123456789abcdef";
  H.Entry = "Game::game";
  H.Target = "x86_64";
  H.Layout = "fedcba9876543210";
  H.StateSize = 8;
  H.InputSize = 8;
  H.OutputSize = 4;
  H.Robots = Robots;
  return H;
}

/// One call of `Name` returning `Result` that writes `Written` at input
/// byte 2 (view offset: state 8 + 2).
CycleRecord callOf(const std::string &Name, Bytes Result, Bytes Written) {
  RecordedCall C;
  C.Name = Name;
  C.Result = std::move(Result);
  if (!Written.empty())
    C.Writes.push_back({1, 2, std::move(Written)});
  CycleRecord R;
  std::string Error;
  size_t Sizes[3] = {8, 8, 4};
  EXPECT_TRUE(encodeCalls({C}, Sizes, R, Error)) << Error;
  return R;
}

std::string writeLog(bool Compress, unsigned Cycles, unsigned Robots = 1) {
  std::string Out;
  llvm::raw_string_ostream OS(Out);
  BinaryLogWriter W(OS, header(Robots), Compress);
  for (uint32_t C = 1; C <= Cycles; ++C)
    for (unsigned R = 0; R < Robots; ++R) {
      Bytes In = {uint8_t(C), 0, 0, 0, uint8_t(R), 0, 0, 7};
      Bytes EntryOut = {1, 2, 3, uint8_t(C - 1)};
      Bytes Out = {1, 2, 3, uint8_t(C)};
      CycleRecord Calls = callOf(C % 2 ? "Sys::random" : "Sys::step",
                                 {uint8_t(C), 0, 0, 0},
                                 C % 3 ? Bytes{} : Bytes{9, 9});
      W.writeCycle(R, C, In, EntryOut, Calls, Out);
    }
  W.finish();
  return Out;
}

TEST(BinaryLogTest, CyclesReadBackAsWritten) {
  for (bool Compress : {false, true}) {
    // 600 cycles: key cycles at 1, 257 and 513, changes in between, and
    // more than one 64 KiB block when uncompressed... of small cycles.
    std::string Log = writeLog(Compress, 600, 2);
    BinaryLogReader R;
    ASSERT_TRUE(R.open(Log)) << R.getError();
    EXPECT_EQ(R.getHeader().Entry, "Game::game");
    EXPECT_EQ(R.getHeader().Robots, 2u);
    BinaryLogCycle C;
    for (uint32_t N = 1; N <= 600; ++N)
      for (unsigned Robot = 0; Robot < 2; ++Robot) {
        ASSERT_TRUE(R.next(C)) << R.getError();
        EXPECT_EQ(C.Cycle, N);
        EXPECT_EQ(C.Robot, Robot);
        EXPECT_EQ(Bytes(C.Input.begin(), C.Input.end()),
                  (Bytes{uint8_t(N), 0, 0, 0, uint8_t(Robot), 0, 0, 7}));
        EXPECT_EQ(Bytes(C.EntryOutput.begin(), C.EntryOutput.end()),
                  (Bytes{1, 2, 3, uint8_t(N - 1)}));
        EXPECT_EQ(Bytes(C.Output.begin(), C.Output.end()),
                  (Bytes{1, 2, 3, uint8_t(N)}));
        ASSERT_EQ(C.NumCalls, 1u);
        CycleRecord Record;
        Record.Calls = C.Calls;
        size_t Sizes[3] = {8, 8, 4};
        std::vector<RecordedCall> Calls = decodeCalls(Record, Sizes);
        ASSERT_EQ(Calls.size(), 1u);
        EXPECT_EQ(Calls[0].Name, N % 2 ? "Sys::random" : "Sys::step");
        EXPECT_EQ(Calls[0].Result, (Bytes{uint8_t(N), 0, 0, 0}));
        EXPECT_EQ(Calls[0].Writes.size(), N % 3 ? 0u : 1u);
      }
    EXPECT_FALSE(R.next(C));
    EXPECT_FALSE(R.failed()) << R.getError();
  }
}

TEST(BinaryLogTest, CompressionShrinksTheLog) {
  EXPECT_LT(writeLog(true, 2000).size(), writeLog(false, 2000).size() / 2);
}

TEST(BinaryLogTest, CallsMoveIntoALargerView) {
  // A robot's log watches no state; the workstation's view has one.
  BinaryLogHeader H = header();
  H.StateSize = 0;
  std::string Out;
  {
    llvm::raw_string_ostream OS(Out);
    BinaryLogWriter W(OS, H, false);
    RecordedCall Call{"Sys::step", {}, false, {}, {{1, 2, {9, 9}}}};
    CycleRecord Calls;
    std::string Error;
    size_t Sizes[3] = {0, 8, 4};
    ASSERT_TRUE(encodeCalls({Call}, Sizes, Calls, Error)) << Error;
    W.writeCycle(0, 1, Bytes(8, 0), Bytes(4, 0), Calls, Bytes(4, 0));
  }
  BinaryLogReader R;
  ASSERT_TRUE(R.open(Out)) << R.getError();
  R.setView(100);
  BinaryLogCycle C;
  ASSERT_TRUE(R.next(C)) << R.getError();
  CycleRecord Record;
  Record.Calls = C.Calls;
  size_t Sizes[3] = {100, 8, 4};
  std::vector<RecordedCall> Calls = decodeCalls(Record, Sizes);
  ASSERT_EQ(Calls.size(), 1u);
  ASSERT_EQ(Calls[0].Writes.size(), 1u);
  EXPECT_EQ(Calls[0].Writes[0].Block, 1u);
  EXPECT_EQ(Calls[0].Writes[0].Offset, 2u);
}

TEST(BinaryLogTest, ErrorsNameTheByteAndTheCycle) {
  std::string Log = writeLog(false, 50);
  BinaryLogReader R;
  EXPECT_FALSE(R.open("{\"recording\":{}}"));
  EXPECT_EQ(R.getError(),
            "byte 0: not a b-script log (it does not start with 'BSLOG')");

  BinaryLogReader Version;
  std::string Other = Log;
  Other[6] = 2;
  EXPECT_FALSE(Version.open(Other));
  EXPECT_EQ(Version.getError(),
            "byte 6: a log of format 2; this bsc reads format 1");

  // Cut inside the one block: its header says more than there is.
  BinaryLogReader Cut;
  EXPECT_FALSE(Cut.open(llvm::StringRef(Log).take_front(Log.size() - 5)));
  EXPECT_NE(Cut.getError().find("the log is cut off"), std::string::npos)
      << Cut.getError();

  // A damaged record tag in the middle: the cycles before it are read.
  std::string Damaged = Log;
  BinaryLogReader Probe;
  ASSERT_TRUE(Probe.open(Log));
  BinaryLogCycle C;
  uint64_t Tenth = 0;
  for (int I = 0; I < 10 && Probe.next(C); ++I)
    Tenth = C.Offset;
  Damaged[Tenth] = 'Z';
  BinaryLogReader D;
  ASSERT_TRUE(D.open(Damaged));
  unsigned Read = 0;
  while (D.next(C))
    ++Read;
  EXPECT_EQ(Read, 9u);
  EXPECT_EQ(D.getError(), "byte " + std::to_string(Tenth) +
                              " (after cycle 9): a record of unknown kind 90");
}
} // namespace

/// A flight log's trace records, as `bsc trace-decode` reads them
/// (readFlightLogTraces): a team's robots apart; a log without them is an
/// error.
TEST(BinaryLogTest, FlightLogTracesDecodeByRobot) {
  // One task with one yield (line 3): slot 1 waits there, 0 is inactive.
  debug::DebugTables Tables;
  debug::DebugTables::Task Task;
  Task.Name = "M::t";
  Task.ShortName = "t";
  Task.File = "M.bs";
  Task.YieldLines = {3};
  Task.YieldValues = {1};
  Tables.Tasks = {Task};
  Tables.RecordSize = 1;

  llvm::SmallString<128> Path;
  ASSERT_FALSE(llvm::sys::fs::createTemporaryFile("flight", "bslog", Path));
  {
    std::error_code EC;
    llvm::raw_fd_ostream OS(Path, EC);
    ASSERT_FALSE(EC);
    BinaryLogWriter W(OS, header(2), /*Compress=*/true);
    Bytes In(8), Out(4);
    for (uint32_t C = 1; C <= 3; ++C)
      for (unsigned R = 0; R < 2; ++R) // Robot 1 runs from cycle 2 on.
        W.writeCycle(R, C, In, Out, CycleRecord(), Out,
                     Bytes{uint8_t(R == 1 && C < 2 ? 0 : 1)});
  }
  DiagnosticEngine Diags;
  auto Cycles = readFlightLogTraces(Path, Tables, Diags);
  ASSERT_TRUE(Cycles) << Diags.getDiagnostics().size();
  ASSERT_EQ(Cycles->size(), 6u);
  EXPECT_EQ((*Cycles)[1].Robot, 1);
  EXPECT_EQ((*Cycles)[1].Cycle, 1u);
  EXPECT_TRUE((*Cycles)[1].Records.empty());
  EXPECT_EQ(debug::formatTraceLine(Tables, (*Cycles)[3].Records),
            "t [running, M.bs:3]");

  // Without trace records: the error names the cycle.
  {
    std::error_code EC;
    llvm::raw_fd_ostream OS(Path, EC);
    ASSERT_FALSE(EC);
    BinaryLogWriter W(OS, header(1), /*Compress=*/false);
    Bytes In(8), Out(4);
    W.writeCycle(0, 1, In, Out, CycleRecord(), Out);
  }
  EXPECT_FALSE(readFlightLogTraces(Path, Tables, Diags));
  ASSERT_EQ(Diags.getDiagnostics().size(), 1u);
  EXPECT_EQ(Diags.getDiagnostics()[0].Kind, diag::err_flight_no_trace);
  llvm::sys::fs::remove(Path);
}
