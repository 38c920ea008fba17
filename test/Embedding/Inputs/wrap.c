/* Runs wrap.bs's tasks across the wrap of the 32-bit cycle counter: the
 * state's cycle starts 3 below 2^32. `ticker` (which prints its count) is
 * not called in the fifth cycle, `count` not in the second; each restarts
 * at its next call. Prints per cycle the cycle number and count's state. */
#include "wrap.h"
#include <stdio.h>

static bs_wrap_state state;

int main(void) {
  if (bs_wrap_init(&state) != BS_INIT_OK)
    return 1;
  bs_state_header *header = (bs_state_header *)&state;
  header->cycle = 0xfffffffdu; /* the next cycle is 2^32 - 2 */
  for (int i = 0; i < 8; ++i) {
    bs_wrap_begin_cycle(&state, 0, 0);
    if (i != 4)
      bs_wrap_call__wrap__ticker(&state);
    if (i != 1)
      bs_wrap_call__wrap__count(&state);
    printf("cycle %u count %d\n", header->cycle,
           (int)bs_wrap_state_of__wrap__count(&state));
    fflush(stdout);
  }
  return 0;
}
