// The paper's Behavior.bs on the robot, compiled with --instrument: feeds
// the inputs of paper.test's approach (cycle n: the ball at
// (800 - 8(n - 1), 600 - 6(n - 1)), time 33n ms) and logs each cycle's
// trace record as bscript.h's "Trace logs" describe, through the inline
// functions of the generated header (behavior.h, behavior name "paper").
// test/REPL/trace-decode-paper.test decodes the log.
#include "SoccerWorld.h"
#include "behavior.h"

#include <cstdio>
#include <cstdlib>

static bs_paper_state State;

int main(int argc, char **argv) {
  if (argc != 3)
    return 2;
  if (int Code = bs_paper_init(&State))
    return bs_report_init_failure(&bs_paper_info, Code);
  std::FILE *Log = std::fopen(argv[1], "wb");
  if (!Log)
    return 2;
  int Cycles = std::atoi(argv[2]);
  for (int N = 1; N <= Cycles; ++N) {
    BehaviorInput In;
    In.ball.position = {800.0f - 8 * (N - 1), 600.0f - 6 * (N - 1)};
    In.time = 33 * N;
    BehaviorOutput Out;
    bs_paper_begin_cycle(&State, &In, &Out);
    bs_paper_trace_begin(&State);
    bs_paper_call__Behavior__gotoBallAndKick(&State);
    uint32_t Cycle = reinterpret_cast<const bs_state_header *>(&State)->cycle;
    std::fwrite(&Cycle, sizeof Cycle, 1, Log);
    std::fwrite(bs_paper_trace_record(&State), 1, BS_PAPER_TRACE_RECORD_SIZE,
                Log);
  }
  std::fclose(Log);
  bs_paper_destroy(&State);
  return 0;
}
