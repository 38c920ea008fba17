/* The cost of tracing on the robot: bs_trace_snapshot after each cycle of
 * bench/Steps.bs (compiled with --instrument --behavior-name steps), for
 * bench/repl.sh. `snapshot_cost N 0|1` runs N cycles without or with it. */
#include <bscript/bscript.h>
#include <stdio.h>
#include <stdlib.h>

extern const bs_behavior_info bs_steps_info;
void bs_steps__Steps__main(void *state);

static unsigned char state[1024] __attribute__((aligned(16)));

int main(int argc, char **argv) {
  if (argc != 3 || bs_steps_info.state_size > sizeof state ||
      bs_state_init(state, &bs_steps_info) != BS_INIT_OK)
    return 1;
  long cycles = atol(argv[1]);
  int trace = atoi(argv[2]);
  bs_activation records[8];
  uint32_t seen = 0;
  for (long i = 0; i < cycles; ++i) {
    bs_begin_cycle(state, 0, 0);
    bs_steps__Steps__main(state);
    if (trace)
      seen += bs_trace_snapshot(state, &bs_steps_info, records, 8);
  }
  printf("%u\n", seen);
  return 0;
}
