// boundary-record.test: a host or i586 program that runs Game.bs as the
// robot would, with sim.cpp's bindings and world.cpp's hooks linked in and
// called where the JIT calls them (lib/JIT/JIT.cpp), printing each cycle's
// output as `bsc run --print-output` does, so that its lines can be
// compared with the JIT's live run and with the exact replay of its
// recording.
#include "game.h"
#include "sim.h"
#include <cstdio>
#include <cstdlib>

extern "C" void *bs_world_init(void *Input, void *Output);
extern "C" void bs_world_begin(void *User, void *Input, void *Output,
                               uint32_t Cycle);
extern "C" void bs_world_end(void *User, const void *Input, void *Output,
                             uint32_t Cycle);
extern "C" void bs_world_exit(void *User);

/// The shortest decimal that reads back as `V`, as bsc prints floats.
static void printFloat(float V) {
  char Buf[32];
  for (int Digits = 1; Digits <= 9; ++Digits) {
    std::snprintf(Buf, sizeof Buf, "%.*g", Digits, double(V));
    if (std::strtof(Buf, nullptr) == V)
      break;
  }
  std::fputs(Buf, stdout);
}

int main(int argc, char **argv) {
  unsigned Cycles = argc > 1 ? unsigned(std::atoi(argv[1])) : 60;
  static bs_game_state State;
  if (bs_game_init(&State) != BS_INIT_OK)
    return 2;
  sim::In In{};
  sim::Out Out{};
  void *User = bs_world_init(&In, &Out);
  bs_state_set_user(&State, User);
  for (uint32_t Cycle = 1; Cycle <= Cycles; ++Cycle) {
    bs_game_begin_cycle(&State, &In, &Out);
    bs_world_begin(User, &In, &Out, Cycle);
    bs_game_call__Game__game(&State);
    bs_world_end(User, &In, &Out, Cycle);
    std::printf("{\"cycle\":%u,\"output\":{\"headMode\":%d,\"motion\":%d,"
                "\"speed\":",
                unsigned(Cycle), Out.headMode, Out.motion);
    printFloat(Out.speed);
    std::printf("}}\n");
  }
  bs_world_exit(User);
  bs_game_destroy(&State);
  return 0;
}
