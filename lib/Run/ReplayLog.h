//===- ReplayLog.h - one log replayed, as bsc replay does it ----*- C++ -*-===//
#ifndef BSC_LIB_RUN_REPLAYLOG_H
#define BSC_LIB_RUN_REPLAYLOG_H

#include "bsc/Run/Run.h"

namespace bsc {

/// Gives a log a SourceMgr of its own while it is replayed: views of the
/// compilation's buffers (so that diagnostics in the behavior keep their
/// places) and, added by the replay, the log's file, which is unmapped
/// when the log is done. Without it every log would stay mapped until the
/// end, and a corpus of thousands would grow without bound.
class LogSources {
public:
  explicit LogSources(llvm::SourceMgr &SM) : SM(SM) {
    llvm::SourceMgr Own;
    Own.setIncludeDirs(SM.getIncludeDirs());
    for (unsigned ID = 1; ID <= SM.getNumBuffers(); ++ID)
      Own.AddNewSourceBuffer(
          llvm::MemoryBuffer::getMemBuffer(
              SM.getMemoryBuffer(ID)->getMemBufferRef(),
              /*RequiresNullTerminator=*/false),
          llvm::SMLoc());
    Saved = std::move(SM);
    SM = std::move(Own);
  }
  ~LogSources() { SM = std::move(Saved); }

private:
  llvm::SourceMgr &SM;
  llvm::SourceMgr Saved;
};

/// Replays the log at `Path` in a fresh session of `L` with `Run`'s
/// options and --world; false if it failed.
llvm::Expected<bool> replayLog(Compilation &C, LoadedBehavior &L,
                               const ReplayLogsOptions &Opts,
                               const std::string &Path, RunOptions Run,
                               uint32_t &Cycles);

} // namespace bsc

#endif
