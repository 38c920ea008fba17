#!/usr/bin/env bash
# A corpus on every core (issue 29): LOGS recordings of CYCLES cycles each
# of the paper's soccer behavior in examples/soccer's closed loop (16 runs
# with the ball in different places, copied to make up LOGS), replayed with
# `bsc replay --jobs JOBS`, against `bsc run --world` and the x86-64 program
# bsc compiles (bench/corpus_native.cpp) running the same cycles. All at
# -O2. Prints cycles per second per core of each, their ratios, the goal
# (the replay in about the time the program needs for the cycles of one
# core, plus one compile) and the peak resident memory of one process
# (GNU time's maximum: the parent or the largest worker), also for a tenth
# of the logs, which must be the same: a replay's memory does not grow
# with the corpus. Then the same corpus as binary logs (.bslog), replayed
# by one process: cycles per second against the native program's (goal:
# a quarter of them).
#
#   bench/corpus.sh [BUILD_DIR] [LOGS] [CYCLES] [JOBS]
#       default: build 200 1000 (all cores); the full size: build 1000 1000
set -euo pipefail
cd "$(dirname "$0")"
BUILD=$(cd "${1:-../build}" && pwd)
LOGS=${2:-200}
CYCLES=${3:-1000}
JOBS=${4:-$(nproc)}
BSC=$BUILD/bin/bsc
SOCCER_O=$BUILD/test/bind-objects/SoccerBindings.host.o
PAPER=$(cd ../../shared/conformance/paper && pwd)
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
TOTAL=$((LOGS * CYCLES))
CXXFLAGS=(-std=c++20 -O2 -I../include -I../examples/soccer -I/usr/include/eigen3)
COMMON=(-O2 --bind "$SOCCER_O" -I "$PAPER" --entry Behavior::gotoBallAndKick)

g++ "${CXXFLAGS[@]}" -fPIC -shared corpus_world.cpp ../examples/soccer/SoccerWorld.cpp -o "$OUT/world.so"
# The native program, as examples/soccer/build-run.sh builds it.
g++ "${CXXFLAGS[@]}" -c ../examples/soccer/SoccerBindings.cpp -o "$OUT/bindings.o"
NATIVE=(-target x86_64 --bind "$OUT/bindings.o" -I "$PAPER" --behavior-name soccer "$PAPER/Behavior.bs")
"$BSC" -O2 -c "${NATIVE[@]}" -o "$OUT/behavior.o"
"$BSC" --emit-header "${NATIVE[@]}" -o "$OUT/behavior.h"
g++ "${CXXFLAGS[@]}" -I "$OUT" corpus_native.cpp ../examples/soccer/SoccerWorld.cpp \
  "$OUT/behavior.o" "$OUT/bindings.o" "$BUILD/lib/libbscript_rt.a" -o "$OUT/native"

# The corpus: 16 runs (fewer if LOGS is smaller), each copied to make up
# LOGS files of CYCLES lines.
mkdir -p "$OUT/corpus" "$OUT/tenth"
RUNS=$((LOGS < 16 ? LOGS : 16))
for ((r = 0; r < RUNS; r++)); do
  BENCH_BALL_X=$((700 + 40 * r)) BENCH_BALL_Y=$((600 - 35 * r)) \
    "$BSC" run "${COMMON[@]}" --world "$OUT/world.so" --world-output /dev/null \
    --cycles "$CYCLES" --record "$OUT/run$r.jsonl" "$PAPER/Behavior.bs"
done
for ((i = 0; i < LOGS; i++)); do
  cp "$OUT/run$((i % RUNS)).jsonl" "$OUT/corpus/log$(printf %05d "$i").jsonl"
done
for ((i = 0; i < (LOGS + 9) / 10; i++)); do
  cp "$OUT/corpus/log$(printf %05d "$i").jsonl" "$OUT/tenth/"
done
size_mb=$(du -sm "$OUT/corpus" | cut -f1)
# The same corpus as binary logs (docs/repl.md "The robot's log"),
# converted without running the behavior.
mkdir -p "$OUT/binary"
for ((r = 0; r < RUNS; r++)); do
  "$BSC" convert --behavior "$PAPER/Behavior.bs" --bind "$SOCCER_O" -I "$PAPER" \
    --entry Behavior::gotoBallAndKick "$OUT/run$r.jsonl" -o "$OUT/run$r.bslog"
done
for ((i = 0; i < LOGS; i++)); do
  cp "$OUT/run$((i % RUNS)).bslog" "$OUT/binary/log$(printf %05d "$i").bslog"
done
binary_kb=$(du -sk "$OUT/binary" | cut -f1)

# timed CMD...: "SECONDS MIB" of one run: wall time and maximum resident set.
timed() {
  /usr/bin/time -f "%e %M" -o "$OUT/time" "$@" > /dev/null
  awk '{ printf "%s %.0f\n", $1, $2 / 1024 }' "$OUT/time"
}
REPLAY=("$BSC" replay "${COMMON[@]}")
RUN=("$BSC" run "${COMMON[@]}" --world "$OUT/world.so" --world-output /dev/null "$PAPER/Behavior.bs")
read -r compile_s _ < <(timed "${RUN[@]}" --cycles 1)
read -r replay_s replay_mb < <(timed "${REPLAY[@]}" --jobs "$JOBS" --logs "$OUT/corpus" "$PAPER/Behavior.bs")
read -r one_s one_mb < <(timed "${REPLAY[@]}" --jobs 1 --logs "$OUT/corpus" "$PAPER/Behavior.bs")
read -r tenth_s tenth_mb < <(timed "${REPLAY[@]}" --jobs 1 --logs "$OUT/tenth" "$PAPER/Behavior.bs")
read -r binary_s binary_mb < <(timed "${REPLAY[@]}" --jobs 1 --logs "$OUT/binary" "$PAPER/Behavior.bs")
RUN_CYCLES=$((TOTAL / JOBS))
read -r run_s run_mb < <(timed "${RUN[@]}" --cycles "$RUN_CYCLES")
read -r native_s _ < <("$OUT/native" 1000000)

echo "corpus: $LOGS logs x $CYCLES cycles = $TOTAL cycles, $size_mb MiB; $JOBS jobs; compile $compile_s s"
awk -v total="$TOTAL" -v jobs="$JOBS" -v c="$compile_s" \
    -v rs="$replay_s" -v os="$one_s" -v us="$run_s" -v ucycles="$RUN_CYCLES" -v ns="$native_s" \
    -v rm="$replay_mb" -v om="$one_mb" -v tm="$tenth_mb" -v um="$run_mb" -v logs="$LOGS" \
    -v bs="$binary_s" -v bm="$binary_mb" -v bk="$binary_kb" '
function rate(cycles, s) { return cycles / (s > c ? s - c : 1e-9) }
BEGIN {
  replay = rate(total / jobs, rs); one = rate(total, os); run = rate(ucycles, us)
  native = 1000000 / ns
  printf "bsc replay --jobs %d   %7.2f s  %9.0f cycles/s/core  %4d MiB peak (one process)\n", jobs, rs, replay, rm
  printf "bsc replay --jobs 1    %7.2f s  %9.0f cycles/s       %4d MiB peak; a tenth of the logs: %d MiB\n", os, one, om, tm
  binary = rate(total, bs)
  printf "binary logs, --jobs 1  %7.2f s  %9.0f cycles/s       %4d MiB peak; the logs: %d KiB (%.1fx the JSON replay, 1/%.1f of native; goal: 1/4)\n", bs, binary, bm, bk, binary / one, native / binary
  printf "bsc run --world        %7.2f s  %9.0f cycles/s       %4d MiB peak (%d cycles, one core)\n", us, run, um, ucycles
  printf "native x86-64          %7.3f s  %9.0f cycles/s       (1,000,000 cycles)\n", ns, native
  printf "replay / run: %.2fx time per cycle (goal 2x); replay / native: %.1fx\n", run / one, native / replay
  goal = total / jobs / native + c
  printf "goal: the corpus in about %.2f s (the native program for %d cycles per core, plus one compile); took %.2f s (%.1fx)\n", goal, total / jobs, rs, rs / goal
}'
