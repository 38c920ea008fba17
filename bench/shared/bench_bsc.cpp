//===- bench_bsc.cpp - a bsc-compiled behavior in the shared harness ------===//
//
// The harness (../../../shared/bench/harness.h) calls bsc_cycle_soccer or
// bsc_cycle_wide once per cycle; here each is one cycle of the compiled
// behavior: bs_begin_cycle and the entry, as robot code does. The program
// holds one behavior (BENCH_WIDE selects which), so the other cycle
// function only reports the mix-up. With BENCH_SNAPSHOT each cycle also
// takes the robot's trace record (bs_trace_snapshot, docs/repl.md), to
// count what logging a trace costs.
//
//===----------------------------------------------------------------------===//
#define BSC_MAIN
#include "harness.h"

#include "behavior.h"

#ifdef BENCH_WIDE
#define BENCH_ENTRY bs_bench_call__wide__cycle
#else
#define BENCH_ENTRY bs_bench_call__soccer__cycle
#endif

static bs_bench_state State;

#ifdef BENCH_SNAPSHOT
static bs_activation Activations[BS_BENCH_NUM_TASKS];
static void snapshot() {
  bs_trace_snapshot(&State, &bs_bench_info, Activations, BS_BENCH_NUM_TASKS);
}
#else
static void snapshot() {}
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
  BENCH_ENTRY(&State);
  snapshot();
#endif
}

extern "C" __attribute__((noinline)) void bsc_cycle_wide() {
#ifdef BENCH_WIDE
  bs_bench_begin_cycle(&State, &g_in, &g_out);
  BENCH_ENTRY(&State);
  snapshot();
#else
  wrongBehavior();
#endif
}

void bsc_reset() {
  bs_bench_destroy(&State);
  if (int Code = bs_bench_init(&State))
    std::exit(bs_report_init_failure(&bs_bench_info, Code));
}

size_t bsc_state_bytes(bool) { return sizeof State; }
int bsc_tasks(bool) { return BS_BENCH_NUM_TASKS; }
#ifdef BENCH_WIDE
const char *bsc_impl = "bsc-wide";
#else
const char *bsc_impl = "bsc-soccer";
#endif
