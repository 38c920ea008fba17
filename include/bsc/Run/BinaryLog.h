//===- BinaryLog.h - the compact log of a robot or a recorded run -*- C++ -*-===//
//
// One binary format for what a robot's flight recorder writes (the runtime's
// flight.c, bscript/flight.h) and for workstation recordings written to a
// `.bslog` file: per cycle the input the entry saw, the calls into
// registered C++ with their effects, and the output the cycle left, each
// as the changes since the cycle before (and whole in key cycles). The
// format is documented in docs/repl.md, "The robot's log"; in short:
//
//   file    = magic "BSLOG" 0x1a (BinaryLogMagic, Basic/ByteCoding.h),
//             uint16 version (1), block...
//   block   = uint32 stored size, uint32 raw size, uint8 codec (0 raw,
//             1 zstd), 3 zero bytes, stored bytes; the raw bytes are
//             records, and no record spans two blocks
//   record  = 'H' header | 'S' more site names | 'C' cycle | 'G' lost cycles
//
// Numbers in records are LEB128, strings a length and their bytes. Calls
// are encoded as CycleRecord::Calls (bsc/JIT/Boundary.h), with the log's
// own numbering of call sites (the header's names, then 'S' records).
//
//===----------------------------------------------------------------------===//
#ifndef BSC_RUN_BINARYLOG_H
#define BSC_RUN_BINARYLOG_H

#include "bsc/Basic/ByteCoding.h"
#include "llvm/ADT/ArrayRef.h"
#include "llvm/ADT/DenseMap.h"
#include "llvm/ADT/StringRef.h"
#include "llvm/Support/raw_ostream.h"
#include <cstdint>
#include <string>
#include <vector>

namespace bsc {

struct CycleRecord;

namespace binlog {
inline constexpr unsigned Version = 1;
inline constexpr size_t FileHeaderSize = 8, BlockHeaderSize = 12;
enum Codec : uint8_t { CodecRaw = 0, CodecZstd = 1 };
enum Tag : uint8_t {
  TagHeader = 'H',
  TagSites = 'S',
  TagCycle = 'C',
  TagGap = 'G',
};
/// A cycle record's flags.
enum CycleFlags : uint8_t {
  CycleKey = 1,      ///< Input and output whole, not changes.
  CycleHasTrace = 2, ///< The `--instrument` trace record follows.
};
} // namespace binlog

/// What a log says of itself (its 'H' record).
struct BinaryLogHeader {
  /// computeBehaviorHash of the behavior that wrote it, and its entry.
  std::string Behavior, Entry;
  /// The target whose memory the bytes are of: `i586` or `x86_64`.
  std::string Target;
  /// getIOLayoutHash of its input and output classes on that target.
  std::string Layout;
  /// The view the calls' writes are offsets into (bsc/JIT/Boundary.h); a
  /// robot's recorder watches no state (0).
  uint64_t StateSize = 0, InputSize = 0, OutputSize = 0;
  unsigned Robots = 1;
  /// The names of the call sites, by number ('H', then 'S' records).
  std::vector<std::string> Sites;
  /// Whether the code that wrote it evaluated its assertions' conditions
  /// (and so made and logged their calls into C++): the JIT always, a
  /// robot's object with --assertions=count or trap.
  bool Assertions = true;
};

/// One cycle as a reader gives it; the arrays stay valid until the next.
struct BinaryLogCycle {
  unsigned Robot = 0;
  uint32_t Cycle = 0;
  /// The byte of the file where its record starts (for messages).
  uint64_t Offset = 0;
  /// The input and the output the entry found (the robot's software may
  /// have changed the output since the cycle before left it), and the
  /// output the cycle left, whole.
  llvm::ArrayRef<unsigned char> Input, EntryOutput, Output;
  /// The calls, encoded as CycleRecord::Calls with this process's site
  /// ids (internBoundaryName) and the reader's view.
  std::vector<unsigned char> Calls;
  unsigned NumCalls = 0;
  /// The `--instrument` trace record of the cycle, if the log has it.
  llvm::ArrayRef<unsigned char> Trace;
};

/// Whether `Bytes` start as a binary log does.
bool isBinaryLog(llvm::StringRef Bytes);

/// Reads a log from memory a cycle at a time. A damaged, truncated or
/// foreign log stops the reading at the record where it fails; the error
/// names its byte and cycle.
class BinaryLogReader {
public:
  /// Reads the file header and the log's header; false with getError().
  bool open(llvm::StringRef Bytes);
  const BinaryLogHeader &getHeader() const { return Header; }
  /// The view the calls are given in (state, input and output sizes);
  /// the log's own unless set. Input and output must be the log's.
  void setView(uint64_t StateSize);
  /// The next cycle; false at the end of the log or on an error.
  bool next(BinaryLogCycle &C);
  bool failed() const { return !Error.empty(); }
  /// "byte N (cycle C of robot R): why".
  const std::string &getError() const { return Error; }
  /// The robots whose cycles the log holds (a team's, counted from 0).
  unsigned countRobots() const { return Header.Robots; }

private:
  bool fail(uint64_t At, std::string Why);
  /// Loads the next block's records; false at the end or on an error.
  bool nextBlock();
  bool readHeaderRecord();
  bool readSites(uint64_t Count);
  /// The file byte of the record at In.P (of its block, if compressed).
  uint64_t recordOffset() const;

  llvm::StringRef File;
  uint64_t BlockAt = 0; ///< The file byte of the next block.
  std::vector<unsigned char> Raw;
  /// The records of the loaded block, read from In.P on.
  ByteReader In;
  uint64_t RawStart = 0; ///< The file byte of the loaded block's records.
  bool Compressed = false;
  BinaryLogHeader Header;
  std::vector<uint32_t> SiteIds; ///< Log site -> internBoundaryName.
  size_t LogView[3] = {0, 0, 0}, View[3] = {0, 0, 0};
  struct Robot {
    /// As the cycle before left them, and what its entry found.
    std::vector<unsigned char> Input, Output, EntryInput, EntryOutput;
    uint32_t Cycle = 0;
    bool Started = false;
  };
  std::vector<Robot> Robots;
  uint32_t LastCycle = 0;
  unsigned LastRobot = 0;
  std::string Error;
};

/// Writes a log: the header, then cycle after cycle, in blocks of about
/// 64 KiB, compressed with zstd unless asked not to.
class BinaryLogWriter {
public:
  BinaryLogWriter(llvm::raw_ostream &OS, BinaryLogHeader H, bool Compress);
  ~BinaryLogWriter() { finish(); }
  /// One cycle of robot `Robot`: the input and output its entry found, its
  /// calls (as recorded, in this process's site ids, over the header's
  /// view), the output the cycle left, and its trace record, if any.
  void writeCycle(unsigned Robot, uint32_t Cycle,
                  llvm::ArrayRef<unsigned char> EntryInput,
                  llvm::ArrayRef<unsigned char> EntryOutput,
                  const CycleRecord &Calls,
                  llvm::ArrayRef<unsigned char> Output,
                  llvm::ArrayRef<unsigned char> Trace = {});
  /// Writes the last block; nothing is written after.
  void finish();

private:
  void flushBlock();

  llvm::raw_ostream &OS;
  BinaryLogHeader Header;
  bool Compress;
  bool Finished = false;
  std::vector<unsigned char> Block;
  llvm::DenseMap<uint32_t, uint32_t> LogSites; ///< Process id -> log site.
  struct Robot {
    std::vector<unsigned char> Input, Output;
    uint32_t Cycles = 0;
  };
  std::vector<Robot> Robots;
};

} // namespace bsc

#endif
