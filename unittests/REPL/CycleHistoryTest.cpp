//===- CycleHistoryTest.cpp - the REPL's input log and state copies -------===//
//
// A toy behavior over bytes: each cycle adds the input to the state. Going
// back restores a copy and re-runs on the logged inputs, which must give
// the state the cycle had the first time.
//
//===----------------------------------------------------------------------===//
#include "bsc/REPL/CycleHistory.h"
#include "gtest/gtest.h"
#include <array>
#include <cstring>

using namespace bsc;

namespace {

/// State: a running sum per input byte and the cycle; input: 7 bytes (not
/// a multiple of 4, so the last word is partial); output: the sum's low byte.
struct Toy {
  std::array<uint32_t, 8> State{};
  std::array<unsigned char, 7> Input{};
  unsigned char Output = 0;

  CycleHistory::Blocks blocks() {
    return {State.data(), Input.data(), &Output};
  }
  void cycle() {
    State[7] += 1;
    for (size_t I = 0; I < Input.size(); ++I)
      State[I] = State[I] * 31 + Input[I];
    Output = static_cast<unsigned char>(State[0]);
  }
  /// The input of cycle `C`: some bytes change every cycle, some rarely.
  static std::array<unsigned char, 7> inputOf(uint32_t C) {
    return {static_cast<unsigned char>(C), 7, 7,
            static_cast<unsigned char>(C / 10), 7, 7,
            static_cast<unsigned char>(C * 3)};
  }
};

/// What the session keeps of a cycle the toy ran: the input its entry saw,
/// no calls into C++.
CycleRecord entryOf(const Toy &T) {
  CycleRecord R;
  R.EntryInput = std::vector<unsigned char>(T.Input.begin(), T.Input.end());
  return R;
}

CycleHistory::Sizes sizes() {
  return {sizeof(Toy::State), sizeof(Toy::Input), sizeof(Toy::Output)};
}

/// Runs the toy `N` cycles from a fresh start, recording each.
std::vector<std::array<uint32_t, 8>> runAndRecord(Toy &T, CycleHistory &H,
                                                  uint32_t N) {
  std::vector<std::array<uint32_t, 8>> States = {T.State};
  H.reset(0, T.blocks());
  for (uint32_t C = 1; C <= N; ++C) {
    T.Input = Toy::inputOf(C);
    CycleRecord R = entryOf(T);
    T.cycle();
    H.recordCycle(R, T.blocks());
    States.push_back(T.State);
  }
  return States;
}

/// Goes to `Target` as the REPL does: restore, then re-run logged cycles.
void travel(Toy &T, const CycleHistory &H, uint32_t Target, bool Before) {
  uint32_t At = H.restore(Target, Before, T.blocks());
  for (uint32_t C = At + 1; C <= Target; ++C) {
    H.applyInput(C, T.Input.data());
    T.cycle();
  }
}

TEST(CycleHistoryTest, ReRunningFromCopiesGivesEveryCycleBack) {
  Toy T;
  CycleHistory H(sizes(), 16);
  auto States = runAndRecord(T, H, 100);
  EXPECT_EQ(H.first(), 0u);
  EXPECT_EQ(H.last(), 100u);
  for (uint32_t C : {0u, 1u, 15u, 16u, 17u, 63u, 64u, 99u, 100u, 3u}) {
    for (bool Before : {false, true}) {
      travel(T, H, C, Before);
      EXPECT_EQ(T.State, States[C]) << "cycle " << C;
      if (C > 0) {
        EXPECT_EQ(T.Input, Toy::inputOf(C)) << "cycle " << C;
      }
    }
  }
}

TEST(CycleHistoryTest, BeforeRunsTheCycleItself) {
  Toy T;
  CycleHistory H(sizes(), 10);
  runAndRecord(T, H, 30);
  EXPECT_EQ(H.restore(20, /*Before=*/false, T.blocks()), 20u);
  EXPECT_EQ(H.restore(20, /*Before=*/true, T.blocks()), 10u);
  EXPECT_EQ(H.restore(0, /*Before=*/true, T.blocks()), 0u);
}

TEST(CycleHistoryTest, OnlyChangedWordsAreLogged) {
  Toy T;
  CycleHistory H(sizes(), 1000);
  H.reset(0, T.blocks());
  size_t Empty = H.getMemoryBytes();
  for (uint32_t C = 1; C <= 1000; ++C) {
    // Neither the input nor the state changes: nothing but the indices.
    H.recordCycle(entryOf(T), T.blocks());
  }
  // Three start indices and a call count per cycle (vector growth aside),
  // no changed words.
  EXPECT_LT(H.getMemoryBytes() - Empty,
            1000 * (3 * sizeof(size_t) + sizeof(unsigned)) * 2 + 64);
}

TEST(CycleHistoryTest, AnEditAtThePromptEndsTheHistoryThere) {
  Toy T;
  CycleHistory H(sizes(), 8);
  auto States = runAndRecord(T, H, 40);
  travel(T, H, 20, true);
  T.State[0] = 12345; // What a line at the prompt did.
  H.keepPresent(20, T.blocks());
  EXPECT_EQ(H.last(), 20u);
  auto Edited = T.State;
  // Live again from 20; a copy at 20 holds the edit.
  for (uint32_t C = 21; C <= 30; ++C) {
    T.Input = Toy::inputOf(C + 100);
    CycleRecord R = entryOf(T);
    T.cycle();
    H.recordCycle(R, T.blocks());
  }
  auto At30 = T.State;
  travel(T, H, 20, /*Before=*/true);
  EXPECT_EQ(T.State, Edited);
  travel(T, H, 30, true);
  EXPECT_EQ(T.State, At30);
  travel(T, H, 10, true);
  EXPECT_EQ(T.State, States[10]);
}

TEST(CycleHistoryTest, AnEditAtTheFirstCycle) {
  Toy T;
  CycleHistory H(sizes(), 4);
  runAndRecord(T, H, 10);
  travel(T, H, 0, false);
  T.State[1] = 7;
  H.keepPresent(0, T.blocks());
  EXPECT_EQ(H.last(), 0u);
  Toy U;
  H.restore(0, true, U.blocks());
  EXPECT_EQ(U.State, T.State);
}

TEST(CycleHistoryTest, LiveViewsAreHowEachCycleLeftTheBlocks) {
  Toy T;
  CycleHistory H(sizes(), 16);
  H.reset(0, T.blocks());
  std::vector<std::vector<unsigned char>> Views;
  auto View = [&] {
    std::vector<unsigned char> V(sizeof T.State + sizeof T.Input + 1);
    std::memcpy(V.data(), T.State.data(), sizeof T.State);
    std::memcpy(V.data() + sizeof T.State, T.Input.data(), sizeof T.Input);
    V.back() = T.Output;
    return V;
  };
  Views.push_back(View());
  for (uint32_t C = 1; C <= 50; ++C) {
    T.Input = Toy::inputOf(C);
    CycleRecord R = entryOf(T);
    R.Calls = {static_cast<unsigned char>(C)}; // Bytes only, here.
    R.NumCalls = 1;
    T.cycle();
    T.Input[0] ^= 0x55; // What C++ wrote during the cycle.
    H.recordCycle(R, T.blocks());
    Views.push_back(View());
  }
  // In order (the cache), backwards and across copies.
  for (uint32_t C : {0u, 1u, 2u, 3u, 17u, 16u, 50u, 49u, 33u, 0u, 31u, 32u})
    EXPECT_EQ(H.liveViewAt(C), Views[C]) << "cycle " << C;
  CycleRecord R;
  H.getCalls(7, R);
  EXPECT_EQ(R.Calls, std::vector<unsigned char>{7});
  EXPECT_EQ(R.NumCalls, 1u);
  // The entry's input, not the one the cycle left.
  travel(T, H, 30, true);
  H.applyInput(31, T.Input.data());
  EXPECT_EQ(T.Input, Toy::inputOf(31));
}

TEST(CycleHistoryTest, AnEditIsTheLiveViewOfItsCycle) {
  Toy T;
  CycleHistory H(sizes(), 8);
  runAndRecord(T, H, 20);
  travel(T, H, 12, true);
  T.State[2] = 99;
  H.keepPresent(12, T.blocks());
  EXPECT_TRUE(H.isEdited(12));
  EXPECT_FALSE(H.isEdited(11));
  uint32_t Word;
  std::memcpy(&Word, H.liveViewAt(12).data() + 8, 4);
  EXPECT_EQ(Word, 99u);
  T.cycle();
  H.recordCycle(entryOf(T), T.blocks());
  std::memcpy(&Word, H.liveViewAt(13).data() + 8, 4);
  EXPECT_EQ(Word, T.State[2]);
}

} // namespace

TEST(CycleHistoryTest, ABrokenCycleIsKeptAsItsCopyWithItsInputAndCalls) {
  Toy T;
  CycleHistory H(sizes(), 8);
  runAndRecord(T, H, 12);
  // Cycle 13 "crashes" half-way: logged, then kept as the moment it left.
  T.Input = Toy::inputOf(113);
  CycleRecord R = entryOf(T);
  T.State[0] = 999;
  H.recordCycle(R, T.blocks());
  H.keepPresent(13, T.blocks(), /*Broken=*/true);
  EXPECT_TRUE(H.isEdited(13));
  EXPECT_TRUE(H.isBroken(13));
  EXPECT_FALSE(H.isBroken(12));
  // Its input is still there for a re-run (which breaks again).
  Toy U;
  H.restore(12, /*Before=*/false, U.blocks());
  H.applyInput(13, U.Input.data());
  EXPECT_EQ(U.Input, Toy::inputOf(113));
  // A prompt's edit is no break.
  H.keepPresent(13, T.blocks());
  EXPECT_TRUE(H.isEdited(13));
  EXPECT_FALSE(H.isBroken(13));
}
