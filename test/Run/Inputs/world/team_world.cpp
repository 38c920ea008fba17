// world.test: a world library for examples/two_robots' behavior in
// `bsc run --world`: its init's result is the robot's blackboard, which the
// behavior's bs::Context functions read (the state's user pointer).
#include "team.h"
#include <cstdint>
#include <cstdio>

extern "C" void *bs_world_init(void *, void *) {
  return new team::Robot{"jit"};
}

extern "C" void bs_world_begin(void *, void *Input, void *, uint32_t Cycle) {
  auto *In = static_cast<team::Input *>(Input);
  In->ballSeen = Cycle >= 2;
  In->ballDistance = 1500.0f - 500.0f * float(Cycle);
}

extern "C" void bs_world_end(void *User, const void *, void *Output,
                             uint32_t Cycle) {
  auto *R = static_cast<team::Robot *>(User);
  std::printf("world: cycle %u, %s head mode %d, pan %d\n", unsigned(Cycle),
              R->name, int(R->headMode),
              static_cast<team::Output *>(Output)->headPan);
}
