//===- BinaryLog.cpp - reading and writing binary logs ---------------------===//
//
// The format (BinaryLog.h, docs/repl.md "The robot's log"). A cycle record:
//   'C', robot, cycle, flags (one byte),
//   input:  whole (input size bytes) in a key cycle, else changes,
//   entry output: the output the entry found, likewise,
//   calls:  their number, their bytes' length, their bytes,
//   output: whole in a key cycle, else changes,
//   trace:  (with CycleHasTrace) a length and the record.
// Changes are runs: their number, then per run the gap after the end of
// the run before (the first: after 0), its length and its bytes. The input
// changes are against the input as the robot's previous cycle left it
// (calls may write it), the entry output's against the output the previous
// cycle left, the output's against the entry output. A robot's first cycle
// is a key cycle.
//
//===----------------------------------------------------------------------===//
#include "bsc/Run/BinaryLog.h"
#include "bsc/JIT/Boundary.h"
#include "llvm/Support/Compression.h"
#include "llvm/Support/Endian.h"
#include "llvm/Support/LEB128.h"
#include <cstring>

using namespace bsc;
using namespace bsc::binlog;

/// The largest raw block a reader takes (BinaryLogReader::nextBlock).
static constexpr uint32_t MaxBlockBytes = 64u << 20;

bool bsc::isBinaryLog(llvm::StringRef Bytes) {
  return Bytes.size() >= sizeof Magic &&
         std::memcmp(Bytes.data(), Magic, sizeof Magic) == 0;
}

//===----------------------------------------------------------------------===//
// Reading
//===----------------------------------------------------------------------===//

namespace {
/// LEB128 numbers and byte strings from a record; a read past the end
/// sets Bad.
struct RecordReader {
  const unsigned char *&P;
  const unsigned char *End;
  bool Bad = false;
  uint64_t uleb() {
    const char *Error = nullptr;
    unsigned N = 0;
    uint64_t V = llvm::decodeULEB128(P, &N, End, &Error);
    if (Error) {
      Bad = true;
      return 0;
    }
    P += N;
    return V;
  }
  llvm::ArrayRef<unsigned char> bytes(uint64_t N) {
    if (Bad || uint64_t(End - P) < N) {
      Bad = true;
      return {};
    }
    llvm::ArrayRef<unsigned char> B(P, size_t(N));
    P += N;
    return B;
  }
  std::string string() {
    llvm::ArrayRef<unsigned char> B = bytes(uleb());
    return std::string(B.begin(), B.end());
  }
  /// `To` whole (a key cycle), or runs of changes to it; false if the
  /// bytes end or a run falls outside it.
  bool state(bool Whole, std::vector<unsigned char> &To) {
    if (!Whole)
      return runs(To);
    llvm::ArrayRef<unsigned char> B = bytes(To.size());
    if (!Bad && !B.empty())
      std::memcpy(To.data(), B.data(), B.size());
    return !Bad;
  }
  /// Applies runs of changes to `To`; false if one falls outside it.
  bool runs(std::vector<unsigned char> &To) {
    uint64_t Count = uleb(), At = 0;
    for (uint64_t I = 0; I < Count && !Bad; ++I) {
      At += uleb();
      uint64_t N = uleb();
      llvm::ArrayRef<unsigned char> B = bytes(N);
      if (Bad || At > To.size() || N > To.size() - At)
        return Bad = true, false;
      std::memcpy(To.data() + At, B.data(), N);
      At += N;
    }
    return !Bad;
  }
};
} // namespace

bool BinaryLogReader::fail(uint64_t At, std::string Why) {
  if (Error.empty()) {
    Error = "byte " + std::to_string(At);
    if (LastCycle)
      Error += " (after cycle " + std::to_string(LastCycle) +
               (Header.Robots > 1 ? " of robot " + std::to_string(LastRobot)
                                  : std::string()) +
               ")";
    Error += ": " + Why;
  }
  return false;
}

bool BinaryLogReader::open(llvm::StringRef Bytes) {
  File = Bytes;
  if (!isBinaryLog(Bytes) || Bytes.size() < FileHeaderSize)
    return fail(0, "not a b-script log (it does not start with 'BSLOG')");
  unsigned Version = llvm::support::endian::read16le(Bytes.data() + 6);
  if (Version != binlog::Version)
    return fail(6, "a log of format " + std::to_string(Version) +
                       "; this bsc reads format " +
                       std::to_string(binlog::Version));
  BlockAt = FileHeaderSize;
  if (!nextBlock())
    return fail(BlockAt, "the log ends before its header");
  return readHeaderRecord();
}

bool BinaryLogReader::nextBlock() {
  if (BlockAt >= File.size())
    return false;
  uint64_t At = BlockAt;
  if (File.size() - At < BlockHeaderSize)
    return fail(At, "the log is cut off in a block's header");
  const char *H = File.data() + At;
  uint32_t Stored = llvm::support::endian::read32le(H);
  uint32_t RawSize = llvm::support::endian::read32le(H + 4);
  uint8_t Codec = uint8_t(H[8]);
  if (H[9] || H[10] || H[11] || Codec > CodecZstd)
    return fail(At, "a damaged block header (codec " + std::to_string(Codec) +
                        ")");
  if (File.size() - At - BlockHeaderSize < Stored)
    return fail(At, "the log is cut off: the block of " +
                        std::to_string(Stored) + " bytes here has " +
                        std::to_string(File.size() - At - BlockHeaderSize));
  auto Data = llvm::ArrayRef<uint8_t>(
      reinterpret_cast<const uint8_t *>(H + BlockHeaderSize), Stored);
  RawStart = At + BlockHeaderSize;
  BlockAt = RawStart + Stored;
  Compressed = Codec == CodecZstd;
  if (!Compressed) {
    if (RawSize != Stored)
      return fail(At, "a damaged block header (raw size " +
                          std::to_string(RawSize) + ", stored " +
                          std::to_string(Stored) + ")");
    P = Data.data();
    End = P + Data.size();
    return true;
  }
  // No writer makes blocks this large (bsc: 64 KiB; a robot: 2 MiB): a
  // damaged size must not decide how much memory the reader takes.
  if (RawSize > MaxBlockBytes)
    return fail(At, "a block of " + std::to_string(RawSize) +
                        " bytes, larger than any writer makes");
  if (!llvm::compression::zstd::isAvailable())
    return fail(At, "the block is compressed with zstd, which this bsc "
                    "was built without");
  Raw.resize(RawSize);
  size_t Size = RawSize;
  if (llvm::Error E =
          llvm::compression::zstd::decompress(Data, Raw.data(), Size)) {
    return fail(At, "a damaged compressed block: " +
                        llvm::toString(std::move(E)));
  }
  if (Size != RawSize)
    return fail(At, "a damaged compressed block (" + std::to_string(Size) +
                        " bytes, its header says " + std::to_string(RawSize) +
                        ")");
  P = Raw.data();
  End = P + Raw.size();
  return true;
}

uint64_t BinaryLogReader::recordOffset() const {
  // A compressed block's records are not the file's bytes: its start.
  if (Compressed)
    return RawStart - BlockHeaderSize;
  return uint64_t(reinterpret_cast<const char *>(P) - File.data());
}

bool BinaryLogReader::readSites(uint64_t Count) {
  RecordReader R{P, End};
  for (uint64_t I = 0; I < Count && !R.Bad; ++I) {
    std::string Name = R.string();
    if (!R.Bad) {
      Header.Sites.push_back(Name);
      SiteIds.push_back(internBoundaryName(Name));
    }
  }
  return !R.Bad;
}

bool BinaryLogReader::readHeaderRecord() {
  auto At = [&] { return recordOffset(); };
  if (P == End || *P != TagHeader)
    return fail(At(), "the log does not start with its header record");
  ++P;
  RecordReader R{P, End};
  Header.Behavior = R.string();
  Header.Entry = R.string();
  Header.Target = R.string();
  Header.Layout = R.string();
  Header.StateSize = R.uleb();
  Header.InputSize = R.uleb();
  Header.OutputSize = R.uleb();
  Header.Robots = unsigned(R.uleb());
  uint64_t NumSites = R.uleb();
  if (R.Bad || !readSites(NumSites))
    return fail(At(), "a damaged header record");
  uint64_t Assertions = R.uleb();
  if (R.Bad || Assertions > 1)
    return fail(At(), "a damaged header record");
  Header.Assertions = Assertions;
  if (Header.Robots == 0 || Header.Robots > 1000)
    return fail(At(), "a header record for " +
                          std::to_string(Header.Robots) + " robots");
  if (Header.InputSize > (1u << 24) || Header.OutputSize > (1u << 24) ||
      Header.StateSize > (1u << 28) ||
      uint64_t(Header.Robots) * (Header.InputSize + Header.OutputSize) >
          (uint64_t(1) << 26))
    return fail(At(), "a header record with implausible sizes");
  LogView[0] = View[0] = Header.StateSize;
  LogView[1] = View[1] = Header.InputSize;
  LogView[2] = View[2] = Header.OutputSize;
  Robots.assign(Header.Robots, Robot());
  for (Robot &Rb : Robots) {
    Rb.Input.assign(Header.InputSize, 0);
    Rb.Output.assign(Header.OutputSize, 0);
  }
  return true;
}

void BinaryLogReader::setView(uint64_t StateSize) { View[0] = StateSize; }

bool BinaryLogReader::next(BinaryLogCycle &C) {
  if (failed())
    return false;
  while (P == End)
    if (!nextBlock())
      return false;
  uint64_t RecordAt = recordOffset();
  uint8_t Tag = *P++;
  RecordReader R{P, End};
  if (Tag == TagSites) {
    uint64_t Count = R.uleb();
    if (R.Bad || !readSites(Count))
      return fail(RecordAt, "a damaged record of site names");
    return next(C);
  }
  if (Tag == TagGap) {
    uint64_t Robot = R.uleb(), First = R.uleb(), Count = R.uleb();
    if (R.Bad)
      return fail(RecordAt, "a damaged record of lost cycles");
    return fail(RecordAt,
                "the robot's recorder lost " + std::to_string(Count) +
                    " cycles from cycle " + std::to_string(First) +
                    (Header.Robots > 1 ? " of robot " + std::to_string(Robot)
                                       : std::string()) +
                    " (it had no free block: the log writer did not keep "
                    "up); a replay cannot go past them");
  }
  if (Tag != TagCycle)
    return fail(RecordAt, "a record of unknown kind " + std::to_string(Tag));
  uint64_t RobotIndex = R.uleb();
  uint64_t Cycle = R.uleb();
  if (R.Bad || R.P == End)
    return fail(RecordAt, "a damaged cycle record");
  uint8_t Flags = *R.P++;
  if (RobotIndex >= Robots.size())
    return fail(RecordAt, "a cycle of robot " + std::to_string(RobotIndex) +
                              "; the log is of " +
                              std::to_string(Robots.size()));
  Robot &Rb = Robots[RobotIndex];
  if (Cycle != uint64_t(Rb.Cycle) + 1 && Rb.Started)
    return fail(RecordAt, "cycle " + std::to_string(Cycle) + " follows cycle " +
                              std::to_string(Rb.Cycle) +
                              (Header.Robots > 1
                                   ? " of robot " + std::to_string(RobotIndex)
                                   : std::string()));
  if (!(Flags & CycleKey) && !Rb.Started)
    return fail(RecordAt, "the first cycle of a robot is not a key cycle");
  auto Damaged = [&](const char *What) {
    return fail(RecordAt, std::string("cycle ") + std::to_string(Cycle) +
                              ": damaged " + What);
  };
  bool Key = Flags & CycleKey;
  if (!R.state(Key, Rb.Input))
    return Damaged("input");
  // The entry's input, before the calls write into it.
  std::vector<unsigned char> EntryInput = Rb.Input;
  if (!R.state(Key, Rb.Output))
    return Damaged("entry output");
  std::vector<unsigned char> EntryOutput = Rb.Output;
  uint64_t NumCalls = R.uleb();
  llvm::ArrayRef<unsigned char> CallBytes = R.bytes(R.uleb());
  if (R.Bad)
    return Damaged("calls");
  C.Calls.clear();
  C.NumCalls = 0;
  std::string Why;
  auto MapId = [&](uint32_t Site) -> std::optional<uint32_t> {
    if (Site < SiteIds.size())
      return SiteIds[Site];
    return std::nullopt;
  };
  if (!translateCalls(CallBytes, MapId, LogView, View, C.Calls, C.NumCalls,
                      Why,
                      [&](unsigned Block, uint64_t Off,
                          llvm::ArrayRef<unsigned char> Bytes) {
                        if (Block == 1)
                          std::memcpy(Rb.Input.data() + Off, Bytes.data(),
                                      Bytes.size());
                      }))
    return fail(RecordAt, "cycle " + std::to_string(Cycle) + ": " + Why);
  if (C.NumCalls != NumCalls)
    return Damaged("calls (their count)");
  if (!R.state(Key, Rb.Output))
    return Damaged("output");
  C.Trace = {};
  if (Flags & CycleHasTrace) {
    C.Trace = R.bytes(R.uleb());
    if (R.Bad)
      return Damaged("trace record");
  }
  Rb.Started = true;
  Rb.Cycle = uint32_t(Cycle);
  LastCycle = uint32_t(Cycle);
  LastRobot = unsigned(RobotIndex);
  Rb.EntryInput = std::move(EntryInput);
  Rb.EntryOutput = std::move(EntryOutput);
  C.Robot = unsigned(RobotIndex);
  C.Cycle = uint32_t(Cycle);
  C.Offset = RecordAt;
  C.Input = Rb.EntryInput;
  C.EntryOutput = Rb.EntryOutput;
  C.Output = Rb.Output;
  return true;
}

//===----------------------------------------------------------------------===//
// Writing
//===----------------------------------------------------------------------===//

namespace {
/// The raw size at which a block is closed.
constexpr size_t BlockBytes = 64 * 1024;
/// Key cycles come this often per robot (and first).
constexpr uint32_t KeyEvery = 256;

void putULEB(std::vector<unsigned char> &Out, uint64_t V) {
  unsigned char Buf[16];
  unsigned N = llvm::encodeULEB128(V, Buf);
  Out.insert(Out.end(), Buf, Buf + N);
}
void putBytes(std::vector<unsigned char> &Out,
              llvm::ArrayRef<unsigned char> B) {
  Out.insert(Out.end(), B.begin(), B.end());
}
void putString(std::vector<unsigned char> &Out, llvm::StringRef S) {
  putULEB(Out, S.size());
  Out.insert(Out.end(), S.begin(), S.end());
}
/// The runs where `Now` differs from `Before` (same size), joined across
/// gaps of fewer than 4 equal bytes.
void putRuns(std::vector<unsigned char> &Out,
             llvm::ArrayRef<unsigned char> Before,
             llvm::ArrayRef<unsigned char> Now) {
  struct Run {
    size_t Start, End;
  };
  llvm::SmallVector<Run, 8> Runs;
  for (size_t I = 0; I < Now.size(); ++I) {
    if (Now[I] == Before[I])
      continue;
    if (!Runs.empty() && I - Runs.back().End < 4)
      Runs.back().End = I + 1;
    else
      Runs.push_back({I, I + 1});
  }
  putULEB(Out, Runs.size());
  size_t Prev = 0;
  for (const Run &R : Runs) {
    putULEB(Out, R.Start - Prev);
    putULEB(Out, R.End - R.Start);
    putBytes(Out, Now.slice(R.Start, R.End - R.Start));
    Prev = R.End;
  }
}
} // namespace

BinaryLogWriter::BinaryLogWriter(llvm::raw_ostream &OS, BinaryLogHeader H,
                                 bool Compress)
    : OS(OS), Header(std::move(H)), Compress(Compress) {
  OS.write(Magic, sizeof Magic);
  char Version[2];
  llvm::support::endian::write16le(Version, binlog::Version);
  OS.write(Version, 2);
  Block.push_back(TagHeader);
  putString(Block, Header.Behavior);
  putString(Block, Header.Entry);
  putString(Block, Header.Target);
  putString(Block, Header.Layout);
  putULEB(Block, Header.StateSize);
  putULEB(Block, Header.InputSize);
  putULEB(Block, Header.OutputSize);
  putULEB(Block, Header.Robots);
  putULEB(Block, Header.Sites.size());
  for (const std::string &S : Header.Sites)
    putString(Block, S);
  putULEB(Block, Header.Assertions);
  for (uint32_t I = 0; I < Header.Sites.size(); ++I)
    LogSites[internBoundaryName(Header.Sites[I])] = I;
  Robots.resize(Header.Robots);
}

void BinaryLogWriter::writeCycle(unsigned RobotIndex, uint32_t Cycle,
                                 llvm::ArrayRef<unsigned char> EntryInput,
                                 llvm::ArrayRef<unsigned char> EntryOutput,
                                 const CycleRecord &Calls,
                                 llvm::ArrayRef<unsigned char> Output,
                                 llvm::ArrayRef<unsigned char> Trace) {
  if (RobotIndex >= Robots.size())
    Robots.resize(RobotIndex + 1);
  Robot &R = Robots[RobotIndex];
  // Names of sites the log has not named yet, before the cycle.
  std::vector<unsigned char> Encoded;
  unsigned NumCalls = 0;
  std::string Error;
  std::vector<std::string> NewSites;
  size_t View[3] = {size_t(Header.StateSize), size_t(Header.InputSize),
                    size_t(Header.OutputSize)};
  auto MapId = [&](uint32_t Id) -> std::optional<uint32_t> {
    auto [It, New] = LogSites.try_emplace(Id, uint32_t(Header.Sites.size()));
    if (New) {
      Header.Sites.push_back(getBoundaryName(Id).str());
      NewSites.push_back(Header.Sites.back());
    }
    return It->second;
  };
  // The input as the cycle leaves it, which the next cycle's changes are
  // against: the entry's, with what the calls wrote into it.
  std::vector<unsigned char> InputAfter(EntryInput.begin(), EntryInput.end());
  translateCalls(Calls.Calls, MapId, View, View, Encoded, NumCalls, Error,
                 [&](unsigned Block, uint64_t Off,
                     llvm::ArrayRef<unsigned char> Bytes) {
                   if (Block == 1 && Off + Bytes.size() <= InputAfter.size())
                     std::memcpy(InputAfter.data() + Off, Bytes.data(),
                                 Bytes.size());
                 });
  if (!NewSites.empty()) {
    Block.push_back(TagSites);
    putULEB(Block, NewSites.size());
    for (const std::string &S : NewSites)
      putString(Block, S);
  }
  bool Key = R.Cycles % KeyEvery == 0;
  Block.push_back(TagCycle);
  putULEB(Block, RobotIndex);
  putULEB(Block, Cycle);
  Block.push_back(uint8_t((Key ? CycleKey : 0) |
                          (Trace.empty() ? 0 : CycleHasTrace)));
  if (Key) {
    putBytes(Block, EntryInput);
    putBytes(Block, EntryOutput);
  } else {
    putRuns(Block, R.Input, EntryInput);
    putRuns(Block, R.Output, EntryOutput);
  }
  putULEB(Block, NumCalls);
  putULEB(Block, Encoded.size());
  putBytes(Block, Encoded);
  if (Key)
    putBytes(Block, Output);
  else
    putRuns(Block, EntryOutput, Output);
  if (!Trace.empty()) {
    putULEB(Block, Trace.size());
    putBytes(Block, Trace);
  }
  R.Input = std::move(InputAfter);
  R.Output.assign(Output.begin(), Output.end());
  ++R.Cycles;
  if (Block.size() >= BlockBytes)
    flushBlock();
}

void BinaryLogWriter::flushBlock() {
  if (Block.empty())
    return;
  llvm::SmallVector<uint8_t, 0> Packed;
  bool Zstd = Compress && llvm::compression::zstd::isAvailable();
  if (Zstd)
    llvm::compression::zstd::compress(Block, Packed,
                                      llvm::compression::zstd::BestSpeedCompression);
  Zstd &= Packed.size() < Block.size();
  llvm::ArrayRef<unsigned char> Stored =
      Zstd ? llvm::ArrayRef<unsigned char>(Packed)
           : llvm::ArrayRef<unsigned char>(Block);
  char Head[BlockHeaderSize] = {};
  llvm::support::endian::write32le(Head, uint32_t(Stored.size()));
  llvm::support::endian::write32le(Head + 4, uint32_t(Block.size()));
  Head[8] = char(Zstd ? CodecZstd : CodecRaw);
  OS.write(Head, sizeof Head);
  OS.write(reinterpret_cast<const char *>(Stored.data()), Stored.size());
  Block.clear();
}

void BinaryLogWriter::finish() {
  if (Finished)
    return;
  flushBlock();
  OS.flush();
  Finished = true;
}
