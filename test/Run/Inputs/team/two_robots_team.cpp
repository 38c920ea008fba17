// team.test: examples/two_robots' loop (robots.cpp) as a team world, so
// that `bsc run --robots 2` prints that example's expected output: each
// robot's user pointer is its own blackboard (bs_team_robot), which the
// behavior reads and writes through bs::Context. Alice (robot 0) sees the
// ball from cycle 2 at 1500 - 500 * cycle; Bob never does.
#include "team.h"
#include <bscript/world.h>
#include <cstdio>

namespace {
team::Robot Boards[2] = {{"alice"}, {"bob"}};
}

extern "C" void *bs_team_init(unsigned) { return Boards; }

extern "C" void *bs_team_robot(void *, unsigned Robot, void *, void *) {
  return &Boards[Robot];
}

extern "C" void bs_team_begin(void *, unsigned Robot, void *Input, void *,
                              uint32_t Cycle) {
  auto &In = *static_cast<team::Input *>(Input);
  if (Robot == 0)
    In = {Cycle >= 2, 1500.0f - 500.0f * float(Cycle)};
  else
    In = {false, 0.0f};
}

extern "C" void bs_team_end(void *, unsigned Robot, const void *,
                            void *Output, uint32_t) {
  const auto &Out = *static_cast<const team::Output *>(Output);
  std::printf("%s: head mode %d, pan %d, speed %g\n", Boards[Robot].name,
              int(Boards[Robot].headMode), Out.headPan, double(Out.walkSpeed));
}
