//===- CycleHistory.cpp - the input log and the state copies ---------------===//
#include "bsc/REPL/CycleHistory.h"
#include <algorithm>
#include <cassert>
#include <cstring>

using namespace bsc;

/// memcpy of `N` bytes, where a block of 0 bytes may be null (a behavior
/// without `input` or `output`).
static void copy(void *To, const void *From, size_t N) {
  if (N)
    std::memcpy(To, From, N);
}

CycleHistory::CycleHistory(Sizes S, unsigned SnapshotEvery)
    : S(S), Every(std::max(1u, SnapshotEvery)) {}

void CycleHistory::takeSnapshot(uint32_t Cycle, bool Edited, Blocks Now) {
  Snapshot Snap{Cycle, Edited, {}};
  Snap.Bytes.resize(S.State + S.Input + S.Output);
  unsigned char *P = Snap.Bytes.data();
  copy(P, Now.State, S.State);
  copy(P + S.State, Now.Input, S.Input);
  copy(P + S.State + S.Input, Now.Output, S.Output);
  Snapshots.push_back(std::move(Snap));
}

void CycleHistory::reset(uint32_t Cycle, Blocks Now) {
  First = Last = Cycle;
  Snapshots.clear();
  Changes.clear();
  Starts.assign(1, 0);
  takeSnapshot(Cycle, /*Edited=*/false, Now);
  LastInput.resize(S.Input);
  copy(LastInput.data(), Now.Input, S.Input);
}

/// The 4-byte word `W` of `Bytes` (the last one padded with zeros).
static uint32_t getWord(const unsigned char *Bytes, size_t Size, uint32_t W) {
  uint32_t V = 0;
  size_t At = size_t(W) * 4;
  copy(&V, Bytes + At, std::min<size_t>(4, Size - At));
  return V;
}

void CycleHistory::recordCycle(Blocks Now) {
  const auto *In = static_cast<const unsigned char *>(Now.Input);
  uint32_t Words = uint32_t((S.Input + 3) / 4);
  for (uint32_t W = 0; W < Words; ++W) {
    uint32_t V = getWord(In, S.Input, W);
    if (V != getWord(LastInput.data(), S.Input, W))
      Changes.push_back({W, V});
  }
  Starts.push_back(Changes.size());
  copy(LastInput.data(), In, S.Input);
  ++Last;
  if ((Last - First) % Every == 0)
    takeSnapshot(Last, /*Edited=*/false, Now);
}

uint32_t CycleHistory::restore(uint32_t Cycle, bool Before,
                               Blocks Into) const {
  assert(Cycle >= First && Cycle <= Last && "outside the history");
  auto It = std::find_if(Snapshots.rbegin(), Snapshots.rend(),
                         [&](const Snapshot &Snap) {
                           if (Snap.Cycle > Cycle)
                             return false;
                           return !Before || Snap.Cycle < Cycle ||
                                  Snap.Edited || Snap.Cycle == First;
                         });
  assert(It != Snapshots.rend() && "the first cycle has a copy");
  const unsigned char *P = It->Bytes.data();
  copy(Into.State, P, S.State);
  copy(Into.Input, P + S.State, S.Input);
  copy(Into.Output, P + S.State + S.Input, S.Output);
  return It->Cycle;
}

void CycleHistory::applyInput(uint32_t Cycle, void *Input) const {
  assert(Cycle > First && Cycle <= Last && "no input logged");
  auto *In = static_cast<unsigned char *>(Input);
  size_t Index = Cycle - First;
  for (size_t I = Starts[Index - 1]; I < Starts[Index]; ++I) {
    size_t At = size_t(Changes[I].Word) * 4;
    copy(In + At, &Changes[I].Value, std::min<size_t>(4, S.Input - At));
  }
}

void CycleHistory::keepPresent(uint32_t Cycle, Blocks Now) {
  assert(Cycle >= First && Cycle <= Last && "outside the history");
  Starts.resize(Cycle - First + 1);
  Changes.resize(Starts.back());
  Last = Cycle;
  while (!Snapshots.empty() && Snapshots.back().Cycle >= Cycle)
    Snapshots.pop_back();
  takeSnapshot(Cycle, /*Edited=*/true, Now);
  LastInput.resize(S.Input);
  copy(LastInput.data(), Now.Input, S.Input);
}

size_t CycleHistory::getMemoryBytes() const {
  size_t Bytes = Changes.capacity() * sizeof(Change) +
                 Starts.capacity() * sizeof(size_t) + LastInput.capacity();
  for (const Snapshot &Snap : Snapshots)
    Bytes += Snap.Bytes.capacity() + sizeof(Snapshot);
  return Bytes;
}
