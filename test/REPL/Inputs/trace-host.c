/* A robot host that logs its behavior's activations as bscript.h's "Trace
 * logs" describe: it starts each cycle's trace record before the entry and
 * writes the cycle number and the record after it. ENTRY names the entry
 * (default: Tasks.bs's main). With -DGENERATED_HEADER it uses the inline
 * functions of `bsc --emit-header` (trace.h) instead of the shim's.
 * test/REPL/trace-decode.test decodes the logs. */
#include <bscript/bscript.h>
#include <stdio.h>

#ifndef ENTRY
#define ENTRY bs_trace__Tasks__main
#endif

#ifdef GENERATED_HEADER
#include "trace.h"
static bs_trace_state state;
#define STATE (&state)
#ifdef BS_TRACE_TRACE_RECORD_SIZE
#define RECORD_SIZE BS_TRACE_TRACE_RECORD_SIZE
#define TRACE_BEGIN() bs_trace_trace_begin(&state)
#define TRACE_RECORD() bs_trace_trace_record(&state)
#else /* A header generated without --instrument. */
#define RECORD_SIZE 0
#define TRACE_BEGIN() ((void)0)
#define TRACE_RECORD() ((const void *)0)
#endif
#else
extern const bs_behavior_info bs_trace_info;
static unsigned char state[65536] __attribute__((aligned(16)));
#define STATE state
#define RECORD_SIZE bs_trace_info.trace.record_size
#define TRACE_BEGIN() bs_trace_begin(state, &bs_trace_info)
#define TRACE_RECORD() bs_trace_record(state, &bs_trace_info)
#endif
void ENTRY(void *state);

int main(int argc, char **argv) {
  if (argc != 3)
    return 1;
#ifdef GENERATED_HEADER
  int init = bs_trace_init(&state); /* checks the state's size */
#else
  if (bs_trace_info.state_size > sizeof state)
    return 1;
  int init = bs_state_init(state, &bs_trace_info);
#endif
  if (init != BS_INIT_OK)
    return bs_report_init_failure(&bs_trace_info, init);
  FILE *log = fopen(argv[1], "wb");
  if (!log)
    return 1;
  int cycles = 0;
  sscanf(argv[2], "%d", &cycles);
  for (int i = 0; i < cycles; ++i) {
    bs_begin_cycle(STATE, 0, 0);
    TRACE_BEGIN();
    ENTRY(STATE);
    uint32_t cycle = ((const bs_state_header *)STATE)->cycle;
    fwrite(&cycle, sizeof cycle, 1, log);
    const void *record = TRACE_RECORD();
    if (record)
      fwrite(record, 1, RECORD_SIZE, log);
  }
  fclose(log);
  printf("debug tables: %s, record: %u bytes, %u-byte slots\n",
         bs_trace_info.debug_tables ? "yes" : "no",
         (unsigned)bs_trace_info.trace.record_size,
         (unsigned)bs_trace_info.trace.slot_bytes);
  return 0;
}
