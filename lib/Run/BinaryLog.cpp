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
#include "bsc/Basic/ByteCoding.h"
#include "llvm/Support/Compression.h"
#include "llvm/Support/Endian.h"
#include <cstring>

using namespace bsc;
using namespace bsc::binlog;

/// The largest raw block a reader takes (BinaryLogReader::nextBlock).
static constexpr uint32_t MaxBlockBytes = 64u << 20;

bool bsc::isBinaryLog(llvm::StringRef Bytes) {
  return Bytes.size() >= sizeof BinaryLogMagic &&
         std::memcmp(Bytes.data(), BinaryLogMagic, sizeof BinaryLogMagic) == 0;
}

//===----------------------------------------------------------------------===//
// Reading
//===----------------------------------------------------------------------===//

namespace {
/// A string: its length, then its bytes.
std::string readString(ByteReader &R) {
  llvm::ArrayRef<unsigned char> B = R.bytes(R.uleb());
  return std::string(B.begin(), B.end());
}

/// Applies runs of changes to `To`; false if the bytes end or a run falls
/// outside it.
bool readRuns(ByteReader &R, std::vector<unsigned char> &To) {
  uint64_t Count = R.uleb(), At = 0;
  for (uint64_t I = 0; I < Count && !R.Bad; ++I) {
    At += R.uleb();
    uint64_t N = R.uleb();
    llvm::ArrayRef<unsigned char> B = R.bytes(N);
    if (R.Bad || At > To.size() || N > To.size() - At)
      return R.Bad = true, false;
    if (N)
      std::memcpy(To.data() + At, B.data(), N);
    At += N;
  }
  return !R.Bad;
}

/// `To` whole (a key cycle), or runs of changes to it.
bool readState(ByteReader &R, bool Whole, std::vector<unsigned char> &To) {
  if (!Whole)
    return readRuns(R, To);
  llvm::ArrayRef<unsigned char> B = R.bytes(To.size());
  if (!R.Bad && !B.empty())
    std::memcpy(To.data(), B.data(), B.size());
  return !R.Bad;
}
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
    In = {Data.data(), Data.data() + Data.size()};
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
  In = {Raw.data(), Raw.data() + Raw.size()};
  return true;
}

uint64_t BinaryLogReader::recordOffset() const {
  // A compressed block's records are not the file's bytes: its start.
  if (Compressed)
    return RawStart - BlockHeaderSize;
  return uint64_t(reinterpret_cast<const char *>(In.P) - File.data());
}

bool BinaryLogReader::readSites(uint64_t Count) {
  ByteReader &R = In;
  for (uint64_t I = 0; I < Count && !R.Bad; ++I) {
    std::string Name = readString(R);
    if (!R.Bad) {
      Header.Sites.push_back(Name);
      SiteIds.push_back(internBoundaryName(Name));
    }
  }
  return !R.Bad;
}

bool BinaryLogReader::readHeaderRecord() {
  auto At = [&] { return recordOffset(); };
  if (In.P == In.End || *In.P != TagHeader)
    return fail(At(), "the log does not start with its header record");
  ++In.P;
  ByteReader &R = In;
  Header.Behavior = readString(R);
  Header.Entry = readString(R);
  Header.Target = readString(R);
  Header.Layout = readString(R);
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
  while (In.P == In.End)
    if (!nextBlock())
      return false;
  uint64_t RecordAt = recordOffset();
  uint8_t Tag = *In.P++;
  ByteReader &R = In;
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
  if (R.Bad || R.P == R.End)
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
  if (!readState(R, Key, Rb.Input))
    return Damaged("input");
  // The entry's input, before the calls write into it.
  std::vector<unsigned char> EntryInput = Rb.Input;
  if (!readState(R, Key, Rb.Output))
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
  if (!readState(R, Key, Rb.Output))
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

void putBytes(std::vector<unsigned char> &Out,
              llvm::ArrayRef<unsigned char> B) {
  Out.insert(Out.end(), B.begin(), B.end());
}
void putString(std::vector<unsigned char> &Out, llvm::StringRef S) {
  appendULEB(Out, S.size());
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
  appendULEB(Out, Runs.size());
  size_t Prev = 0;
  for (const Run &R : Runs) {
    appendULEB(Out, R.Start - Prev);
    appendULEB(Out, R.End - R.Start);
    putBytes(Out, Now.slice(R.Start, R.End - R.Start));
    Prev = R.End;
  }
}
} // namespace

BinaryLogWriter::BinaryLogWriter(llvm::raw_ostream &OS, BinaryLogHeader H,
                                 bool Compress)
    : OS(OS), Header(std::move(H)), Compress(Compress) {
  OS.write(BinaryLogMagic, sizeof BinaryLogMagic);
  char Version[2];
  llvm::support::endian::write16le(Version, binlog::Version);
  OS.write(Version, 2);
  Block.push_back(TagHeader);
  putString(Block, Header.Behavior);
  putString(Block, Header.Entry);
  putString(Block, Header.Target);
  putString(Block, Header.Layout);
  appendULEB(Block, Header.StateSize);
  appendULEB(Block, Header.InputSize);
  appendULEB(Block, Header.OutputSize);
  appendULEB(Block, Header.Robots);
  appendULEB(Block, Header.Sites.size());
  for (const std::string &S : Header.Sites)
    putString(Block, S);
  appendULEB(Block, Header.Assertions);
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
    appendULEB(Block, NewSites.size());
    for (const std::string &S : NewSites)
      putString(Block, S);
  }
  bool Key = R.Cycles % KeyEvery == 0;
  Block.push_back(TagCycle);
  appendULEB(Block, RobotIndex);
  appendULEB(Block, Cycle);
  Block.push_back(uint8_t((Key ? CycleKey : 0) |
                          (Trace.empty() ? 0 : CycleHasTrace)));
  if (Key) {
    putBytes(Block, EntryInput);
    putBytes(Block, EntryOutput);
  } else {
    putRuns(Block, R.Input, EntryInput);
    putRuns(Block, R.Output, EntryOutput);
  }
  appendULEB(Block, NumCalls);
  appendULEB(Block, Encoded.size());
  putBytes(Block, Encoded);
  if (Key)
    putBytes(Block, Output);
  else
    putRuns(Block, EntryOutput, Output);
  if (!Trace.empty()) {
    appendULEB(Block, Trace.size());
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
