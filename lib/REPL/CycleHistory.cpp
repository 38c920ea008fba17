//===- CycleHistory.cpp - the logs of inputs, calls and views, the copies -===//
#include "bsc/REPL/CycleHistory.h"
#include "llvm/Support/LEB128.h"
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

void CycleHistory::copyView(Blocks Now,
                            std::vector<unsigned char> &Into) const {
  Into.resize(S.State + S.Input + S.Output);
  unsigned char *P = Into.data();
  copy(P, Now.State, S.State);
  copy(P + S.State, Now.Input, S.Input);
  copy(P + S.State + S.Input, Now.Output, S.Output);
}

void CycleHistory::takeSnapshot(uint32_t Cycle, bool Edited, Blocks Now) {
  Snapshot Snap{Cycle, Edited, false, {}};
  copyView(Now, Snap.Bytes);
  Snapshots.push_back(std::move(Snap));
}

void CycleHistory::reset(uint32_t Cycle, Blocks Now) {
  First = Last = Cycle;
  Snapshots.clear();
  Changes.clear();
  Starts.assign(1, 0);
  ViewChanges.clear();
  ViewStarts.assign(1, 0);
  Calls.clear();
  CallStarts.assign(1, 0);
  CallCounts.clear();
  CacheValid = false;
  takeSnapshot(Cycle, /*Edited=*/false, Now);
  copyView(Now, LastView);
}

/// The 4-byte word `W` of `Bytes` (the last one padded with zeros).
static uint32_t getWord(const unsigned char *Bytes, size_t Size, uint32_t W) {
  uint32_t V = 0;
  size_t At = size_t(W) * 4;
  if (At + 4 <= Size) // A whole word: one load (the common case).
    std::memcpy(&V, Bytes + At, 4);
  else
    copy(&V, Bytes + At, Size - At);
  return V;
}

void CycleHistory::recordCycle(const CycleRecord &Cycle, Blocks Now) {
  // The input the entry saw, against the input the cycle before left.
  const unsigned char *OldInput = LastView.data() + S.State;
  if (Cycle.EntryInput.size() == S.Input) {
    uint32_t Words = uint32_t((S.Input + 3) / 4);
    for (uint32_t W = 0; W < Words; ++W) {
      uint32_t V = getWord(Cycle.EntryInput.data(), S.Input, W);
      if (V != getWord(OldInput, S.Input, W))
        Changes.push_back({W, V});
    }
  }
  Starts.push_back(Changes.size());
  Calls.insert(Calls.end(), Cycle.Calls.begin(), Cycle.Calls.end());
  CallStarts.push_back(Calls.size());
  CallCounts.push_back(Cycle.NumCalls);
  // How the cycle left the view, against how the one before left it.
  std::vector<unsigned char> &View = Scratch; // No allocation per cycle.
  copyView(Now, View);
  size_t Size = View.size();
  uint32_t Words = uint32_t((Size + 3) / 4), Next = 0;
  for (uint32_t W = 0; W < Words; ++W) {
    uint32_t V = getWord(View.data(), Size, W);
    if (V == getWord(LastView.data(), Size, W))
      continue;
    unsigned char Buf[8];
    unsigned N = llvm::encodeULEB128(W - Next, Buf);
    ViewChanges.insert(ViewChanges.end(), Buf, Buf + N);
    auto *B = reinterpret_cast<const unsigned char *>(&V);
    ViewChanges.insert(ViewChanges.end(), B, B + 4);
    Next = W + 1;
  }
  ViewStarts.push_back(ViewChanges.size());
  std::swap(LastView, Scratch);
  ++Last;
  if ((Last - First) % Every == 0)
    takeSnapshot(Last, /*Edited=*/false, Now);
}

void CycleHistory::getCalls(uint32_t Cycle, CycleRecord &Into) const {
  assert(Cycle > First && Cycle <= Last && "no calls logged");
  size_t Index = Cycle - First;
  Into.clear();
  Into.Calls.assign(Calls.begin() + CallStarts[Index - 1],
                    Calls.begin() + CallStarts[Index]);
  Into.NumCalls = CallCounts[Index - 1];
}

const CycleHistory::Snapshot &
CycleHistory::snapshotAtOrBefore(uint32_t Cycle) const {
  auto It = std::find_if(Snapshots.rbegin(), Snapshots.rend(),
                         [&](const Snapshot &Snap) {
                           return Snap.Cycle <= Cycle;
                         });
  assert(It != Snapshots.rend() && "the first cycle has a copy");
  return *It;
}

bool CycleHistory::isEdited(uint32_t Cycle) const {
  const Snapshot &Snap = snapshotAtOrBefore(Cycle);
  return Snap.Cycle == Cycle && Snap.Edited;
}

const std::vector<unsigned char> &
CycleHistory::liveViewAt(uint32_t Cycle) const {
  assert(Cycle >= First && Cycle <= Last && "outside the history");
  const Snapshot &Snap = snapshotAtOrBefore(Cycle);
  uint32_t From;
  if (CacheValid && CachedCycle <= Cycle && CachedCycle >= Snap.Cycle) {
    From = CachedCycle;
  } else {
    Cached = Snap.Bytes;
    From = Snap.Cycle;
  }
  size_t Size = Cached.size();
  for (uint32_t C = From + 1; C <= Cycle; ++C) {
    size_t Index = C - First;
    const unsigned char *P = ViewChanges.data() + ViewStarts[Index - 1];
    const unsigned char *End = ViewChanges.data() + ViewStarts[Index];
    uint32_t Next = 0;
    while (P < End) {
      unsigned N = 0;
      uint32_t W = Next + uint32_t(llvm::decodeULEB128(P, &N, End));
      P += N;
      size_t At = size_t(W) * 4;
      copy(Cached.data() + At, P, std::min<size_t>(4, Size - At));
      P += 4;
      Next = W + 1;
    }
  }
  CachedCycle = Cycle;
  CacheValid = true;
  return Cached;
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

bool CycleHistory::isBroken(uint32_t Cycle) const {
  const Snapshot &Snap = snapshotAtOrBefore(Cycle);
  return Snap.Cycle == Cycle && Snap.Broken;
}

void CycleHistory::keepPresent(uint32_t Cycle, Blocks Now, bool Broken) {
  assert(Cycle >= First && Cycle <= Last && "outside the history");
  size_t Index = Cycle - First;
  Starts.resize(Index + 1);
  Changes.resize(Starts.back());
  ViewStarts.resize(Index + 1);
  ViewChanges.resize(ViewStarts.back());
  CallStarts.resize(Index + 1);
  Calls.resize(CallStarts.back());
  CallCounts.resize(Index);
  Last = Cycle;
  while (!Snapshots.empty() && Snapshots.back().Cycle >= Cycle)
    Snapshots.pop_back();
  takeSnapshot(Cycle, /*Edited=*/true, Now);
  Snapshots.back().Broken = Broken;
  copyView(Now, LastView);
  CacheValid = false;
}

size_t CycleHistory::getMemoryBytes() const {
  size_t Bytes = Changes.capacity() * sizeof(Change) +
                 Starts.capacity() * sizeof(size_t) + LastView.capacity() +
                 Scratch.capacity() +
                 ViewChanges.capacity() +
                 ViewStarts.capacity() * sizeof(size_t) + Calls.capacity() +
                 CallStarts.capacity() * sizeof(size_t) +
                 CallCounts.capacity() * sizeof(unsigned) + Cached.capacity();
  for (const Snapshot &Snap : Snapshots)
    Bytes += Snap.Bytes.capacity() + sizeof(Snapshot);
  return Bytes;
}
