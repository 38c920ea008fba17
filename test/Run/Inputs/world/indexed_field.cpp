// team.test: a one-robot world (cabsl's Striker) that learns which robot it
// is from bs_world_robot: robot K sees the ball 100 * K further away, so the
// robots of `--robots N` are not identical twins.
#include "../cabsl/world.h"
#include <cstdint>
#include <cstdio>

namespace {
struct Field {
  unsigned Robot = 0, Robots = 1;
};
} // namespace

extern "C" void *bs_world_init(void *, void *) { return new Field; }

extern "C" void bs_world_robot(void *User, unsigned Robot, unsigned Robots) {
  auto *F = static_cast<Field *>(User);
  F->Robot = Robot;
  F->Robots = Robots;
  std::printf("robot %u of %u\n", Robot, Robots);
}

extern "C" void bs_world_begin(void *User, void *Input, void *, uint32_t Cycle) {
  auto *I = static_cast<sw::In *>(Input);
  I->time = int(Cycle - 1) * 100;
  I->ballDistance = 150.0f + 100.0f * float(static_cast<Field *>(User)->Robot);
  I->ballSeen = true;
}

extern "C" void bs_world_exit(void *User) { delete static_cast<Field *>(User); }
