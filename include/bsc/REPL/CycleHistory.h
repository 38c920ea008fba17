//===- CycleHistory.h - what the REPL keeps to go back in time -*- C++ -*-===//
//
// A behavior is deterministic given its inputs, and its state is one plain
// block of bytes, so the REPL travels in time by re-execution: it logs the
// input every cycle saw and copies the state (with input and output) every
// few cycles; going to cycle N restores the last copy at or before N and
// runs the cycles after it again on their logged inputs.
//
// The input log keeps, per cycle, only the 4-byte words of the input that
// changed since the cycle before, so a robot whose input changes in a few
// fields costs a few bytes per cycle. This class holds bytes only; the REPL
// (ReplTime.cpp) decides when to record, restore and re-run.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_REPL_CYCLEHISTORY_H
#define BSC_REPL_CYCLEHISTORY_H

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

  /// After cycle last() + 1 ran for the first time: logs the input it saw
  /// and, every SnapshotEvery cycles, copies the blocks.
  void recordCycle(Blocks Now);

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
  /// the copy at `Cycle`.
  void keepPresent(uint32_t Cycle, Blocks Now);

  /// The bytes held (logs and copies), for the benchmark and `:history`.
  size_t getMemoryBytes() const;
  unsigned getSnapshotEvery() const { return Every; }

private:
  struct Snapshot {
    uint32_t Cycle;
    bool Edited; ///< Taken by keepPresent.
    std::vector<unsigned char> Bytes; ///< State, input, output.
  };
  struct Change {
    uint32_t Word;
    uint32_t Value;
  };
  void takeSnapshot(uint32_t Cycle, bool Edited, Blocks Now);

  Sizes S;
  unsigned Every;
  uint32_t First = 0, Last = 0;
  std::vector<Snapshot> Snapshots; ///< By cycle.
  /// Cycle c's changed input words: Changes[Starts[c - First - 1] ..
  /// Starts[c - First]).
  std::vector<Change> Changes;
  std::vector<size_t> Starts;
  /// The input of cycle Last as logged (the base of the next change list).
  std::vector<unsigned char> LastInput;
};

} // namespace bsc

#endif
