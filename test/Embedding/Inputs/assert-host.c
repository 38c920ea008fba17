/* A robot host of a behavior compiled with `--assertions=count`: after
 * each cycle it reads every assertion's counter through bscript.h
 * (bs_assertion_failures) and its place from the table; at the end the
 * runtime's bs_report_assertions. Used by test/Embedding/assertions.test. */
#include <bscript/bscript.h>
#include <stdio.h>

extern const bs_behavior_info bs_robot_info;
void bs_robot__Asserts__main(void *state);
static unsigned char state[4096] __attribute__((aligned(16)));

int main(void) {
  if (bs_robot_info.state_size > sizeof state)
    return 1;
  int init = bs_state_init(state, &bs_robot_info);
  if (init != BS_INIT_OK)
    return bs_report_init_failure(&bs_robot_info, init);
  const bs_assertion_layout *a = &bs_robot_info.assertions;
  printf("mode %u, %u assertions\n", (unsigned)a->mode,
         (unsigned)a->num_assertions);
  for (uint32_t k = 0; k < a->num_assertions; ++k)
    printf("%u: %s:%u:%u in %s: %s (%s)\n", (unsigned)k, a->assertions[k].file,
           (unsigned)a->assertions[k].line, (unsigned)a->assertions[k].column,
           a->assertions[k].owner, a->assertions[k].condition,
           a->assertions[k].message ? a->assertions[k].message : "no message");
  for (int i = 0; i < 5; ++i) {
    bs_begin_cycle(state, 0, 0);
    bs_robot__Asserts__main(state);
    printf("cycle %d:", i + 1);
    for (uint32_t k = 0; k < a->num_assertions; ++k)
      printf(" %u", (unsigned)bs_assertion_failures(state, &bs_robot_info, k));
    printf("\n");
  }
  fflush(stdout);
  return bs_report_assertions(state, &bs_robot_info);
}
