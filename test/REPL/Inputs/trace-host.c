/* A robot host that logs its behavior's activations as bscript.h's "Trace
 * logs" describe: after each cycle, {cycle, count} and the records of
 * bs_trace_snapshot. test/REPL/trace-decode.test decodes the log. */
#include <bscript/bscript.h>
#include <stdio.h>

extern const bs_behavior_info bs_trace_info;
void bs_trace__Tasks__main(void *state);

static unsigned char state[4096] __attribute__((aligned(16)));

int main(int argc, char **argv) {
  if (argc != 3 || bs_trace_info.state_size > sizeof state ||
      bs_state_init(state, &bs_trace_info) != BS_INIT_OK)
    return 1;
  FILE *log = fopen(argv[1], "wb");
  if (!log)
    return 1;
  int cycles = 0;
  sscanf(argv[2], "%d", &cycles);
  for (int i = 0; i < cycles; ++i) {
    bs_begin_cycle(state, 0, 0);
    bs_trace__Tasks__main(state);
    bs_activation records[8];
    uint32_t header[2];
    header[0] = ((const bs_state_header *)state)->cycle;
    header[1] = bs_trace_snapshot(state, &bs_trace_info, records, 8);
    fwrite(header, sizeof header[0], 2, log);
    fwrite(records, sizeof records[0], header[1], log);
  }
  fclose(log);
  printf("debug tables: %s\n", bs_trace_info.debug_tables ? "yes" : "no");
  return 0;
}
