// destroy.test: the robot stops a behavior whose running task holds C++
// values in the state; bs_holder_destroy (bs_state_destroy) destroys them.
#include "holder.h"
#include <cstdio>

namespace lc {
int live(); // test/Bindings/Inputs/lifecycle.cpp: Counted values alive
}

static bs_holder_state State;

int main() {
  if (bs_holder_init(&State) != BS_INIT_OK)
    return 2;
  // A zeroed state holds nothing: destroying it does nothing.
  bs_holder_destroy(&State);
  std::printf("fresh: %d alive\n", lc::live());
  for (int Cycle = 0; Cycle < 3; ++Cycle) {
    bs_holder_begin_cycle(&State, nullptr, nullptr);
    bs_holder_call__holder__hold(&State);
    bs_holder_call__holder__once(&State);
  }
  std::printf("running: %d alive\n", lc::live());
  bs_holder_destroy(&State);
  std::printf("destroyed: %d alive\n", lc::live());
  bs_holder_destroy(&State); // again: nothing left to destroy
  std::printf("again: %d alive\n", lc::live());
  // Initialised again, the same storage runs a new behavior.
  if (bs_state_init(&State, &bs_holder_info) != BS_INIT_OK)
    return 2;
  bs_holder_begin_cycle(&State, nullptr, nullptr);
  bs_holder_call__holder__hold(&State);
  std::printf("restarted: %d alive\n", lc::live());
  bs_state_destroy(&State, &bs_holder_info);
  std::printf("end: %d alive\n", lc::live());
  return 0;
}
