//===- bench_bsc.cpp - a bsc-compiled behavior in the shared harness ------===//
//
// The harness (../../../shared/bench/harness.h) calls bsc_cycle_soccer or
// bsc_cycle_wide once per cycle; here each is one cycle of the compiled
// behavior: bs_begin_cycle and the entry, as robot code does. The program
// holds one behavior (BENCH_WIDE selects which), so the other cycle
// function only reports the mix-up. With BENCH_TRACE (and a behavior
// compiled with --instrument) each cycle also starts its trace record
// (bs_bench_trace_begin, docs/repl.md), which the behavior's task calls
// write; with BENCH_TRACE_LOG as well, the record is then copied into a log
// ring in memory, as a robot that logs its trace does: the two costs of
// tracing on the robot. With BENCH_FLIGHT (a behavior compiled with
// --flight-recorder) each cycle is recorded by the flight recorder
// (bscript/flight.h) into blocks of 16 KiB, whose bytes a callback counts
// (a robot's would queue them for its log writer); the program prints
// them per cycle on stderr when it ends.
//
//===----------------------------------------------------------------------===//
#define BSC_MAIN
#include "harness.h"

#include "behavior.h"

#include <cstring>

#ifdef BENCH_WIDE
#define BENCH_ENTRY bs_bench_call__wide__cycle
#else
#define BENCH_ENTRY bs_bench_call__soccer__cycle
#endif

static bs_bench_state State;

#ifdef BENCH_TRACE
static void startTrace() { bs_bench_trace_begin(&State); }
#else
static void startTrace() {}
#endif

#ifdef BENCH_TRACE_LOG
// 256 cycles of records; a logger thread would write them out.
// Not static: the copies are the point, so the compiler must keep them.
alignas(4) unsigned char Log[256][BS_BENCH_TRACE_RECORD_SIZE];
static unsigned NextRecord = 0;
static void logTrace() {
  std::memcpy(Log[NextRecord++ % 256], bs_bench_trace_record(&State),
              BS_BENCH_TRACE_RECORD_SIZE);
}
#else
static void logTrace() {}
#endif

#ifdef BENCH_FLIGHT
#include <bscript/flight.h>
alignas(8) static unsigned char FlightMemory[1 << 17];
static bs_flight_recorder Recorder;
static unsigned long long FlightBytes, FlightCycles;
static void countBlock(void *, const void *, uint32_t Size) {
  FlightBytes += Size;
}
static void flightBegin() { bs_flight_begin(&Recorder, &State); }
static void flightEnd() {
  bs_flight_end(&Recorder, &State);
  ++FlightCycles;
}
static void flightReport() {
  bs_flight_flush(&Recorder);
  std::fprintf(stderr, "flight: %llu bytes in %llu cycles, %u lost\n",
               FlightBytes, FlightCycles, bs_flight_lost(&Recorder));
}
static void flightStart() {
  static bool Reporting = false;
  if (!Reporting)
    std::atexit(flightReport);
  Reporting = true;
#ifdef BENCH_WIDE
  const char *Entry = "wide::cycle";
#else
  const char *Entry = "soccer::cycle";
#endif
  bs_flight_config Config = {&bs_bench_flight, &bs_bench_info, Entry,
                             FlightMemory, sizeof FlightMemory, 16384, 4, 0,
                             countBlock, nullptr};
  if (int Code = bs_flight_start(&Recorder, &Config)) {
    std::fprintf(stderr, "bench: bs_flight_start: %d\n", Code);
    std::exit(2);
  }
}
#else
static void flightBegin() {}
static void flightEnd() {}
static void flightStart() {}
#endif

static void wrongBehavior() {
  std::fprintf(stderr, "bench: this program holds the %s behavior\n",
               bsc_impl);
  std::exit(2);
}

extern "C" __attribute__((noinline)) void bsc_cycle_soccer() {
#ifdef BENCH_WIDE
  wrongBehavior();
#else
  bs_bench_begin_cycle(&State, &g_in, &g_out);
  startTrace();
  flightBegin();
  BENCH_ENTRY(&State);
  flightEnd();
  logTrace();
#endif
}

extern "C" __attribute__((noinline)) void bsc_cycle_wide() {
#ifdef BENCH_WIDE
  bs_bench_begin_cycle(&State, &g_in, &g_out);
  startTrace();
  flightBegin();
  BENCH_ENTRY(&State);
  flightEnd();
  logTrace();
#else
  wrongBehavior();
#endif
}

void bsc_reset() {
  bs_bench_destroy(&State);
  if (int Code = bs_bench_init(&State))
    std::exit(bs_report_init_failure(&bs_bench_info, Code));
  flightStart();
}

size_t bsc_state_bytes(bool) { return sizeof State; }
int bsc_tasks(bool) { return BS_BENCH_NUM_TASKS; }
#ifdef BENCH_WIDE
const char *bsc_impl = "bsc-wide";
#else
const char *bsc_impl = "bsc-soccer";
#endif
