/*===- report.c - why a program cannot start its behavior -----------------===*
 *
 * The message a program that bsc links prints when bs_state_init refuses
 * its state. Like io.c it uses stdio, so it is kept out of bscript.c; an
 * embedding that has no stderr calls bs_check_bindings and reports in its
 * own way.
 *===----------------------------------------------------------------------===*/
#include "bscript/bscript.h"
#include <stdio.h>

int bs_report_init_failure(const bs_behavior_info *info, int code) {
  const char *stale = bs_check_bindings(info);
  if (code == BS_INIT_STALE_BINDINGS && stale)
    fprintf(stderr,
            "bscript: error: the behavior was compiled against binding "
            "module '%s' whose descriptor has changed (sizes, offsets or "
            "signatures); recompile the scripts\n",
            stale);
  else if (code == BS_INIT_WRONG_SIZE)
    fprintf(stderr,
            "bscript: error: the behavior's state has %u bytes, but its "
            "header says otherwise; regenerate the header with the options "
            "of the object (--instrument, -target)\n",
            (unsigned)info->state_size);
  else
    fprintf(stderr, "bscript: error: cannot initialise the behavior state "
                    "(ABI version or alignment, code %d)\n",
            code);
  return 1;
}
