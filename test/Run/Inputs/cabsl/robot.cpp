// cabsl_option.test: the robot side of the idiom, for host and i586
// programs: feeds the same inputs as inputs.jsonl (time in steps of 100,
// the ball near from cycle 3, not seen in cycle 5) and prints what the
// behavior wrote, one line per cycle, as `bsc run --print-output` does.
#include "striker.h"
#include "world.h"
#include <cstdio>

int main() {
  static bs_striker_state State;
  if (bs_striker_init(&State) != BS_INIT_OK)
    return 2;
  sw::In In{};
  sw::Out Out{};
  for (int Cycle = 1; Cycle <= 13; ++Cycle) {
    In.time = (Cycle - 1) * 100;
    In.ballDistance = Cycle < 3 ? 500.0f : 150.0f;
    In.ballSeen = Cycle != 5;
    bs_striker_begin_cycle(&State, &In, &Out);
    bs_striker_call__Striker__striker(&State);
    std::printf("{\"cycle\":%d,\"output\":{\"kickPower\":%g,\"motion\":%d}}\n",
                Cycle, Out.kickPower, Out.motion);
  }
  bs_striker_destroy(&State);
  return 0;
}
