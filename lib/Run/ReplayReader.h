//===- ReplayReader.h - a recording read as its cycles come ----*- C++ -*-===//
#ifndef BSC_LIB_RUN_REPLAYREADER_H
#define BSC_LIB_RUN_REPLAYREADER_H

#include "bsc/Run/BinaryLog.h"
#include "bsc/Run/Run.h"
#include <optional>

namespace bsc {

/// One line of a replay file: the objects a replay uses.
struct ReplayLine {
  llvm::SMLoc Loc; ///< Its first character.
  /// The JSON text of its `input` and `output` (empty if it has none),
  /// checked: a replay writes the one and compares the other from the
  /// text, and parses them only where the text is not the plain form a
  /// recording has (Runner.cpp).
  llvm::StringRef Input, Output;
  /// A team recording's `robot` (docs/repl.md "A team in one process").
  std::optional<unsigned> Robot;
  /// The JSON text of its `calls` (recordCycle), empty if it has none.
  llvm::StringRef Calls;
  /// The JSON text of its `tasks` (recordCycle), empty if it has none:
  /// read only to explain a failure (RunOptions::Explain).
  llvm::StringRef Tasks;
  /// A binary log's cycle instead of text: input and output as bytes, the
  /// calls decoded (valid until the next line).
  const BinaryLogCycle *Logged = nullptr;
};

/// A recording's first line (recordHeader); recordings of format 1 have
/// none.
struct RecordingHeader {
  unsigned Format = 1;
  std::string Behavior, Entry;
  /// A binary log (BinaryLog.h), of a robot or a workstation.
  bool Binary = false;
  /// Whether its calls include those of assertions' conditions
  /// (BinaryLogHeader::Assertions; recordings: always).
  bool Assertions = true;
};

/// Reads a JSONL replay file a line at a time, as its cycles come: the
/// file is in the SourceMgr (mapped, so that its errors have carets), and
/// of the current line only `input` and `output` are parsed, so a replay
/// takes the same memory whatever its length and skips the `tasks` a
/// recording carries. A damaged line stops the replay at its cycle.
/// A binary log (bsc/Run/BinaryLog.h) is read a cycle at a time likewise.
class ReplayReader {
public:
  ReplayReader(Compilation &C, const LoadedBehavior &L) : C(C), L(L) {}

  /// Reads the file and its header line, if any; false after reporting
  /// (also a file with no line).
  bool open(llvm::StringRef Path);
  const RecordingHeader &getHeader() const { return Header; }
  /// The next line, checked; false at the end or after reporting it
  /// (failed()).
  bool next(ReplayLine &Line);
  bool failed() const { return Failed; }
  /// How many robots the recording's first cycle has lines for: its
  /// leading lines with `robot` 0, 1, ... (1 without `robot`). Reads
  /// ahead without moving on.
  unsigned countRobots() const;

private:
  bool read(llvm::StringRef Raw, ReplayLine &Line);
  /// Reports what is wrong with a line the scan could not take apart, by
  /// parsing it whole (`invalid JSON: ...` at the byte, or not an object).
  bool reportDamaged(llvm::StringRef Raw);
  /// Takes the header line if `Raw` is one; false after reporting a bad
  /// one. `IsHeader` says whether it was.
  bool readHeader(llvm::StringRef Raw, bool &IsHeader);
  /// Opens the binary log `Bytes` and checks that its bytes are this
  /// workstation's; false after reporting.
  bool openLog(llvm::StringRef Bytes);

  Compilation &C;
  const LoadedBehavior &L;
  llvm::StringRef Rest;
  bool Failed = false;
  RecordingHeader Header;
  std::string Path;
  std::optional<BinaryLogReader> Log;
  BinaryLogCycle Logged;
};

} // namespace bsc

#endif
