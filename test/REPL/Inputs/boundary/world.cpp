// The world library of the boundary tests: the blackboard behind the user
// pointer, a button pressed every 7th cycle, and an end hook that prints
// and, built with -DEND_WRITES_OUTPUT, changes `output` after the behavior
// (which time travel must take from its record; a regression replay runs
// no end hook, so a recording of that world differs there).
#include "sim.h"
#include <cstdio>

extern "C" void *bs_world_init(void *, void *) { return new sim::Board{}; }

extern "C" void bs_world_begin(void *, void *Input, void *, uint32_t Cycle) {
  static_cast<sim::In *>(Input)->button = Cycle % 7 == 0;
}

extern "C" void bs_world_end(void *User, const void *, void *Output,
                             uint32_t Cycle) {
  auto *O = static_cast<sim::Out *>(Output);
#ifdef END_WRITES_OUTPUT
  O->speed *= 0.5f;
#endif
  std::printf("world: end of cycle %u, motion %d, %d head writes\n",
              unsigned(Cycle), O->motion, static_cast<sim::Board *>(User)->writes);
}

extern "C" void bs_world_exit(void *User) { delete static_cast<sim::Board *>(User); }
