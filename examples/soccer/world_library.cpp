// A world library (`bsc run --world`, `bsc repl --world`) around this
// folder's world, for bench/repl.sh's figures and the timeline's tests: the
// robot walks to the ball, kicks it 2 m away, and walks after it, so the
// input changes every cycle.
#include "SoccerSim.h"

extern "C" void *bs_world_init(void *, void *) {
  return new soccer::World({1000, 600}, {4500, 0});
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
