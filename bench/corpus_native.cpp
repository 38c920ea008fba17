// bench/corpus.sh's reference: the paper's soccer behavior compiled by bsc
// for x86-64, linked into a program that runs it in examples/soccer's
// closed loop as `bsc run --world` does (one input and output object, the
// world before and after each cycle). Prints the seconds CYCLES cycles took.
#include "SoccerSim.h"
#include "behavior.h"
#include <chrono>
#include <cstdio>
#include <cstdlib>

int main(int argc, char **argv) {
  long Cycles = argc > 1 ? std::atol(argv[1]) : 1000000;
  static bs_soccer_state State;
  if (bs_soccer_init(&State) != 0)
    return 2;
  soccer::World W({1000, 600}, {4500, 0});
  BehaviorInput In;
  BehaviorOutput Out;
  auto Start = std::chrono::steady_clock::now();
  for (long I = 0; I < Cycles; ++I) {
    W.fillInput(In);
    bs_soccer_begin_cycle(&State, &In, &Out);
    bs_soccer_call__Behavior__gotoBallAndKick(&State);
    W.step(Out);
  }
  double Seconds = std::chrono::duration<double>(
                       std::chrono::steady_clock::now() - Start)
                       .count();
  bs_soccer_destroy(&State);
  // The output, so that the loop is not optimised away.
  std::printf("%.6f %d\n", Seconds, int(Out.motion));
  return 0;
}
