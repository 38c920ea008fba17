//===- CycleHistory.h - what the REPL keeps to go back in time -*- C++ -*-===//
//
// A behavior is deterministic given its inputs and what its calls into
// registered C++ did, and its state is one plain block of bytes, so the
// REPL travels in time by re-execution: it logs the input every cycle's
// entry saw and the cycle's calls (bsc/JIT/Boundary.h), and copies the
// state (with input and output) every few cycles; going to cycle N restores
// the last copy at or before N and runs the cycles after it again on their
// logged inputs, taking each call from the log instead of calling the C++.
//
// A re-run checks itself: the history also logs how the state, input and
// output were left by each live cycle, so every re-run cycle is compared
// with the live one (liveViewAt) and a difference is found at the cycle
// where it arises (a binding that wrote memory the recorder cannot see).
//
// The logs keep, per cycle, only the 4-byte words that changed since the
// cycle before, so a robot whose input changes in a few fields costs a few
// bytes per cycle. This class holds bytes only; the REPL (ReplTime.cpp)
// decides when to record, restore and re-run.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_REPL_CYCLEHISTORY_H
#define BSC_REPL_CYCLEHISTORY_H

#include "bsc/JIT/Boundary.h"
#include <cstddef>
#include <cstdint>
#include <vector>

namespace bsc {

class CycleHistory {
public:
  /// The sizes of the blocks kept: the state, the input and the output.
  struct Sizes {
    size_t State = 0, Input = 0, Output = 0;
  };
  /// The bytes of a moment between cycles (const for recording).
  struct Blocks {
    void *State, *Input, *Output;
  };

  /// A copy of the state every `SnapshotEvery` cycles (at least 1).
  CycleHistory(Sizes S, unsigned SnapshotEvery);

  /// Forgets everything: the history starts at `Cycle` with these bytes.
  void reset(uint32_t Cycle, Blocks Now);
  /// The first and the last cycle the history can go to.
  uint32_t first() const { return First; }
  uint32_t last() const { return Last; }

  /// After cycle last() + 1 ran for the first time: logs the input its
  /// entry saw and its calls (`Calls`), how it left the blocks, and every
  /// SnapshotEvery cycles copies them.
  void recordCycle(const CycleRecord &Calls, Blocks Now);
  /// Cycle `Cycle`'s calls, as recordCycle got them (without the input).
  void getCalls(uint32_t Cycle, CycleRecord &Into) const;
  /// The state, input and output as the live cycle `Cycle` left them
  /// (first() <= Cycle <= last()), end to end. Cheap for consecutive
  /// cycles.
  const std::vector<unsigned char> &liveViewAt(uint32_t Cycle) const;
  /// Whether the prompt changed the blocks at `Cycle` (keepPresent): its
  /// copy, not a re-run, is that moment.
  bool isEdited(uint32_t Cycle) const;

  /// Restores the latest copy taken at or before `Cycle` (first() <= Cycle
  /// <= last()) and returns its cycle. `Before`: a copy strictly before
  /// `Cycle` unless Cycle is first() or the copy at Cycle was taken after
  /// the prompt changed the state (see keepPresent), so that at least the
  /// cycle itself runs again.
  uint32_t restore(uint32_t Cycle, bool Before, Blocks Into) const;
  /// Sets `Input`, which holds the input of cycle Cycle - 1 as the history
  /// has it, to that of `Cycle` (first() < Cycle <= last()).
  void applyInput(uint32_t Cycle, void *Input) const;

  /// The prompt changed the state or input at `Cycle` (<= last()): the
  /// cycles after it are forgotten and the blocks as they are now become
  /// the copy at `Cycle`. `Broken`: no prompt did, cycle `Cycle` crashed
  /// or failed an assertion (its input and calls are logged up to there).
  void keepPresent(uint32_t Cycle, Blocks Now, bool Broken = false);
  /// Whether the copy at `Cycle` is of a cycle that broke (keepPresent).
  bool isBroken(uint32_t Cycle) const;

  /// The bytes held (logs and copies), for the benchmark and `:history`.
  size_t getMemoryBytes() const;
  unsigned getSnapshotEvery() const { return Every; }

private:
  struct Snapshot {
    uint32_t Cycle;
    bool Edited; ///< Taken by keepPresent.
    bool Broken; ///< Of a cycle that broke (keepPresent).
    std::vector<unsigned char> Bytes; ///< State, input, output.
  };
  struct Change {
    uint32_t Word;
    uint32_t Value;
  };
  void takeSnapshot(uint32_t Cycle, bool Edited, Blocks Now);
  /// The blocks end to end.
  void copyView(Blocks Now, std::vector<unsigned char> &Into) const;
  const Snapshot &snapshotAtOrBefore(uint32_t Cycle) const;

  Sizes S;
  unsigned Every;
  uint32_t First = 0, Last = 0;
  std::vector<Snapshot> Snapshots; ///< By cycle.
  /// Cycle c's changed input words: Changes[Starts[c - First - 1] ..
  /// Starts[c - First]).
  std::vector<Change> Changes;
  std::vector<size_t> Starts;
  /// The blocks as cycle Last left them (the base of the next changes),
  /// and recordCycle's copy of the blocks now.
  std::vector<unsigned char> LastView, Scratch;
  /// Cycle c's changed view words (ULEB128 distance to the word after the
  /// last one, then the word): ViewChanges[ViewStarts[c - First - 1] ..
  /// ViewStarts[c - First]).
  std::vector<unsigned char> ViewChanges;
  std::vector<size_t> ViewStarts;
  /// Cycle c's calls (Boundary.cpp's encoding), likewise.
  std::vector<unsigned char> Calls;
  std::vector<size_t> CallStarts;
  std::vector<unsigned> CallCounts;
  /// liveViewAt's last answer.
  mutable std::vector<unsigned char> Cached;
  mutable uint32_t CachedCycle = 0;
  mutable bool CacheValid = false;
};

} // namespace bsc

#endif
