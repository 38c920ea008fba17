// Runs the goalie behavior for three cycles.
#include "goalie.h"

int main() {
  bs_goalie_state State;
  if (bs_goalie_init(&State) != 0)
    return 1;
  for (int Cycle = 0; Cycle < 3; ++Cycle) {
    bs_goalie_begin_cycle(&State, nullptr, nullptr);
    bs_goalie_call__goalie__main(&State);
  }
  bs_goalie_destroy(&State);
  return 0;
}
