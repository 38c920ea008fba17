// world.test: a host or i586 program that runs cabsl's Striker in the
// closed loop of `bsc run --world field.so --cycles 13`, with field.cpp's
// hooks linked in (compiled for the program's target, -m32 for i586) and
// called where the JIT calls them (lib/JIT/JIT.cpp): bs_world_init once,
// its result the state's user pointer; each cycle bs_world_begin before
// the entry and bs_world_end after it; bs_world_exit at the end.
#include "striker.h"
#include "world.h"
#include <cstdint>
#include <cstdio>

extern "C" void *bs_world_init(void *Input, void *Output);
extern "C" void bs_world_begin(void *User, void *Input, void *Output,
                               uint32_t Cycle);
extern "C" void bs_world_end(void *User, const void *Input, void *Output,
                             uint32_t Cycle);
extern "C" void bs_world_exit(void *User);

int main() {
  static bs_striker_state State;
  if (bs_striker_init(&State) != BS_INIT_OK)
    return 2;
  sw::In In{};
  sw::Out Out{};
  void *User = bs_world_init(&In, &Out);
  bs_state_set_user(&State, User);
  for (uint32_t Cycle = 1; Cycle <= 13; ++Cycle) {
    bs_striker_begin_cycle(&State, &In, &Out);
    bs_world_begin(User, &In, &Out, Cycle);
    bs_striker_call__Striker__striker(&State);
    bs_world_end(User, &In, &Out, Cycle);
  }
  bs_world_exit(User);
  bs_striker_destroy(&State);
  return 0;
}
