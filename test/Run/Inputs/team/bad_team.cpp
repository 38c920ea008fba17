// team.test: team worlds (bscript/world.h) that go wrong, one per -D:
// CRASH_INIT (bs_team_init), CRASH_ROBOT1 (bs_team_begin of robot 1 in
// cycle 2), NO_BEGIN (no bs_team_begin: not a team world), and without any
// a counting world that prints each hook's call.
#include <bscript/world.h>
#include <cstdio>

namespace {
int Team = 7; // What bs_team_init returns: its address is the team.
}

extern "C" void *bs_team_init(unsigned Robots) {
#ifdef CRASH_INIT
  volatile int *P = nullptr;
  *P = 1;
#endif
  std::printf("init %u robots\n", Robots);
  return &Team;
}

#ifndef NO_BEGIN
extern "C" void bs_team_begin(void *T, unsigned Robot, void *, void *,
                              uint32_t Cycle) {
#ifdef CRASH_ROBOT1
  if (Robot == 1 && Cycle == 2) {
    volatile int *P = nullptr;
    *P = 1;
  }
#endif
  std::printf("begin robot %u cycle %u%s\n", Robot, Cycle,
              T == &Team ? "" : " (not the team)");
}
#endif

extern "C" void bs_team_end(void *, unsigned Robot, const void *, void *,
                            uint32_t Cycle) {
  std::printf("end robot %u cycle %u\n", Robot, Cycle);
}

extern "C" void bs_team_exit(void *T) {
  std::printf("exit%s\n", T == &Team ? "" : " (not the team)");
}
