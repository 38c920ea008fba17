/*===- flight_program.c - the flight log of a program bsc links ------------===*
 *
 * A program that bsc links with --flight-recorder (its `main` runs the
 * cycles) records its flight log into the file $BS_FLIGHT_LOG names, and
 * nothing without it: the recorder's memory is static, its full blocks are
 * written with stdio. A robot program gives the recorder its own memory
 * and log writer instead (bscript/flight.h); like report.c this file uses
 * stdio, so it is kept apart from the recorder.
 *===----------------------------------------------------------------------===*/
#include "bscript/flight.h"
#include <stdio.h>
#include <stdlib.h>

static bs_flight_recorder program_recorder;
static FILE *program_log;
/* 16 blocks of 16 KiB and the world's objects (64 KiB at most each). */
static unsigned char program_memory[16 * 16392 + 3 * 65536]
    __attribute__((aligned(8)));

static void write_block(void *user, const void *bytes, uint32_t size) {
  (void)user;
  fwrite(bytes, 1, size, program_log);
}

bs_flight_recorder *bs_flight_program_start(const bs_flight_table *table,
                                            const bs_behavior_info *info,
                                            const char *entry) {
  const char *path = getenv("BS_FLIGHT_LOG");
  if (!path || !*path)
    return 0;
  program_log = fopen(path, "wb");
  if (!program_log) {
    fprintf(stderr, "bscript: error: cannot write the flight log '%s'\n",
            path);
    return 0;
  }
  bs_flight_config config = {table, info, entry, program_memory,
                             sizeof program_memory, 16384, 16, 0,
                             write_block, 0};
  int code = bs_flight_start(&program_recorder, &config);
  if (code != BS_FLIGHT_OK) {
    fprintf(stderr, "bscript: error: the flight recorder refused to start "
                    "(code %d, bscript/flight.h)\n", code);
    fclose(program_log);
    return 0;
  }
  return &program_recorder;
}

void bs_flight_program_end(bs_flight_recorder *recorder) {
  if (!recorder)
    return;
  bs_flight_flush(recorder);
  if (bs_flight_lost(recorder))
    fprintf(stderr, "bscript: warning: the flight log lost %u cycles\n",
            (unsigned)bs_flight_lost(recorder));
  fclose(program_log);
}
