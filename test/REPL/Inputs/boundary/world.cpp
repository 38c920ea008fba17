// The world library of the boundary tests: the blackboard behind the user
// pointer, a button pressed every 7th cycle, and an end hook that prints
// and changes `output` after the behavior.
#include "sim.h"
#include <cstdio>

extern "C" void *bs_world_init(void *, void *) { return new sim::Board{}; }

extern "C" void bs_world_begin(void *, void *Input, void *, uint32_t Cycle) {
  static_cast<sim::In *>(Input)->button = Cycle % 7 == 0;
}

extern "C" void bs_world_end(void *User, const void *, void *Output,
                             uint32_t Cycle) {
  auto *O = static_cast<sim::Out *>(Output);
  O->speed *= 0.5f;
  std::printf("world: end of cycle %u, motion %d, %d head writes\n",
              unsigned(Cycle), O->motion, static_cast<sim::Board *>(User)->writes);
}

extern "C" void bs_world_exit(void *User) { delete static_cast<sim::Board *>(User); }
