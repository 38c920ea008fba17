/* Used by stale.test: a robot program that embeds the behavior stale.bs
 * (header from bsc --emit-header) the way docs/embedding.md says, and
 * reports a stale binding module by name before running anything. */
#include "stale.h"
#include <stdio.h>

extern const char bs_module_Stale[];

int main(void) {
  static bs_stale_state state;
  /* The runtime's hash of the descriptor linked here; bsc --dump-bindings
   * prints the one it compiled against. */
  printf("linked descriptor hash 0x%016llx\n",
         (unsigned long long)bs_binding_hash(bs_module_Stale));
  fflush(stdout);
  int code = bs_stale_init(&state);
  if (code != BS_INIT_OK) {
    const char *stale = bs_check_bindings(&bs_stale_info);
    fprintf(stderr, "robot: stale binding module: %s\n", stale ? stale : "-");
    return bs_report_init_failure(&bs_stale_info, code);
  }
  bs_stale_begin_cycle(&state, NULL, NULL);
  bs_stale_call__stale__main(&state);
  return 0;
}
