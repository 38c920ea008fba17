/* A robot host of a behavior compiled with `--cycle-budget` (and
 * `--instrument`): after each cycle it asks bscript.h which loop ran out
 * (bs_budget_ran_out) and logs the cycle's trace record for `bsc
 * trace-decode`; at the end it prints the budget record. Used by
 * test/Embedding/cycle-budget.test. */
#include <bscript/bscript.h>
#include <stdio.h>

extern const bs_behavior_info bs_budget_info;
void bs_budget__Spin__main(void *state);
static unsigned char state[65536] __attribute__((aligned(16)));

int main(int argc, char **argv) {
  if (argc != 3 || bs_budget_info.state_size > sizeof state)
    return 1;
  int init = bs_state_init(state, &bs_budget_info);
  if (init != BS_INIT_OK)
    return bs_report_init_failure(&bs_budget_info, init);
  FILE *log = fopen(argv[1], "wb");
  if (!log)
    return 1;
  int cycles = 0;
  sscanf(argv[2], "%d", &cycles);
  for (int i = 0; i < cycles; ++i) {
    bs_begin_cycle(state, 0, 0);
    bs_trace_begin(state, &bs_budget_info);
    bs_budget__Spin__main(state);
    uint32_t cycle = ((const bs_state_header *)state)->cycle;
    fwrite(&cycle, sizeof cycle, 1, log);
    fwrite(bs_trace_record(state, &bs_budget_info), 1,
           bs_budget_info.trace.record_size, log);
    const bs_loop_info *loop = bs_budget_ran_out(state, &bs_budget_info);
    if (loop)
      printf("cycle %u: ran out in the loop of %s at line %u (task %d)\n",
             (unsigned)cycle, loop->owner, (unsigned)loop->line,
             (int)loop->task);
    else
      printf("cycle %u: within the budget\n", (unsigned)cycle);
  }
  fclose(log);
  const bs_budget_record *record = bs_budget_record_at(state, &bs_budget_info);
  printf("budget %u passes, %u loops; ran out %u times, last in loop %u in "
         "cycle %u\n",
         (unsigned)bs_budget_info.budget.budget,
         (unsigned)bs_budget_info.budget.num_loops, (unsigned)record->ran_out,
         (unsigned)record->loop, (unsigned)record->loop_cycle);
  return 0;
}
