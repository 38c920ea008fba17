/*===- report.c - what a program tells about its behavior -----------------===*
 *
 * The messages a program that bsc links prints when bs_state_init refuses
 * its state, when a cycle ran out of its budget (`--cycle-budget`), and
 * which assertions failed (`--assertions=count`).
 * Like io.c it uses stdio, so it is kept out of bscript.c; an embedding
 * that has no stderr calls bs_check_bindings and bs_budget_ran_out and
 * reports in its own way.
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
            "of the object (--instrument, --cycle-budget, --assertions, "
            "-target)\n",
            (unsigned)info->state_size);
  else
    fprintf(stderr, "bscript: error: cannot initialise the behavior state "
                    "(ABI version or alignment, code %d)\n",
            code);
  return 1;
}

int bs_report_budget(const void *state, const bs_behavior_info *info) {
  const bs_loop_info *loop = bs_budget_ran_out(state, info);
  if (!loop)
    return 0;
  fprintf(stderr,
          "bscript: warning: cycle %u ran out of its budget of %u loop "
          "passes in the loop of '%s' at line %u, which %s\n",
          (unsigned)((const bs_state_header *)state)->cycle,
          (unsigned)info->budget.budget, loop->owner, (unsigned)loop->line,
          loop->task >= 0 ? "failed the task" : "returned its zero");
  return 1;
}

int bs_report_assertions(const void *state, const bs_behavior_info *info) {
  int failed = 0;
  for (uint32_t i = 0; i < info->assertions.num_assertions; ++i) {
    uint32_t count = bs_assertion_failures(state, info, i);
    if (!count)
      continue;
    const bs_assertion_info *a = &info->assertions.assertions[i];
    fprintf(stderr,
            "bscript: error: %s:%u:%u: assertion '%s' in '%s' failed %u "
            "time%s%s%s\n",
            a->file, (unsigned)a->line, (unsigned)a->column, a->condition,
            a->owner, (unsigned)count, count == 1 ? "" : "s",
            a->message ? ": " : "", a->message ? a->message : "");
    failed = 1;
  }
  return failed;
}
