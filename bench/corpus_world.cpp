// bench/corpus.sh's world (and test/REPL/replay-triage.test's):
// examples/soccer's closed loop (as world_library.cpp) with the ball where
// BENCH_BALL_X and BENCH_BALL_Y say, so that each recording of the corpus
// is a run of its own.
#include "SoccerSim.h"
#include <cstdlib>

static int fromEnv(const char *Name, int Default) {
  const char *V = std::getenv(Name);
  return V ? std::atoi(V) : Default;
}

extern "C" void *bs_world_init(void *, void *) {
  return new soccer::World(
      {fromEnv("BENCH_BALL_X", 1000), fromEnv("BENCH_BALL_Y", 600)},
      {4500, 0});
}
extern "C" void bs_world_begin(void *User, void *Input, void *, uint32_t) {
  static_cast<soccer::World *>(User)->fillInput(
      *static_cast<BehaviorInput *>(Input));
}
extern "C" void bs_world_end(void *User, const void *, void *Output,
                             uint32_t) {
  static_cast<soccer::World *>(User)->step(
      *static_cast<const BehaviorOutput *>(Output));
}
