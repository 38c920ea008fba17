#!/usr/bin/env bash
# Replay against run (issue 29): the paper's soccer behavior in a closed
# loop with examples/soccer/world_library.cpp for CYCLES cycles, recorded,
# then replayed; the reference in the same run is `bsc run` of the same
# cycles with the world. Prints wall time (best of 3) and peak memory
# (GNU time's maximum resident set) of each, and their ratios. With
# --instructions, also the instructions per cycle of each (callgrind, the
# difference between 2,000 and 6,000 cycles, so that the compile cancels
# out), which the shared machine's load does not move.
#
#   bench/replay.sh [BUILD_DIR] [CYCLES] [--instructions]
#       (default: build 20000)
set -euo pipefail
cd "$(dirname "$0")"
BUILD=$(cd "${1:-../build}" && pwd)
CYCLES=${2:-20000}
BSC=$BUILD/bin/bsc
SOCCER_O=$BUILD/test/bind-objects/SoccerBindings.host.o
PAPER=$(cd ../../shared/conformance/paper && pwd)
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT

g++ -std=c++20 -O2 -fPIC -shared -I../examples/soccer -I/usr/include/eigen3 \
  ../examples/soccer/world_library.cpp ../examples/soccer/SoccerWorld.cpp -o "$OUT/world.so"
COMMON=(--bind "$SOCCER_O" -I "$PAPER" --entry Behavior::gotoBallAndKick)
"$BSC" run "${COMMON[@]}" --world "$OUT/world.so" --world-output /dev/null \
  --cycles "$CYCLES" --record "$OUT/rec.jsonl" "$PAPER/Behavior.bs"

# peak CMD...: the maximum resident set of CMD in MiB.
peak() { /usr/bin/time -f %M "$@" 2>&1 >/dev/null | tail -n 1 | awk '{ printf "%.0f", $1 / 1024 }'; }
RUN=("$BSC" run "${COMMON[@]}" --world "$OUT/world.so" --world-output /dev/null --cycles "$CYCLES" "$PAPER/Behavior.bs")
REPLAY=("$BSC" run "${COMMON[@]}" --replay "$OUT/rec.jsonl" "$PAPER/Behavior.bs")
run_s=$(python3 best_time.py 3 "${RUN[@]}")
replay_s=$(python3 best_time.py 3 "${REPLAY[@]}")
run_mb=$(peak "${RUN[@]}")
replay_mb=$(peak "${REPLAY[@]}")
size_mb=$(awk -v b="$(stat -c %s "$OUT/rec.jsonl")" 'BEGIN { printf "%.1f", b / 1048576 }')
echo "soccer, $CYCLES cycles; recording $size_mb MiB"
echo "bsc run (world)     $run_s s, $run_mb MiB peak"
echo "bsc run --replay    $replay_s s, $replay_mb MiB peak"
awk -v a="$replay_s" -v b="$run_s" 'BEGIN { printf "replay / run: %.1fx time (goal 2x)\n", a / b }'
[[ ${3:-} == --instructions ]] || exit 0

# instructions CMD...: what callgrind counts for CMD.
instructions() {
  valgrind --tool=callgrind --callgrind-out-file=/dev/null "$@" 2>&1 >/dev/null |
    sed -n 's/.*Collected : \([0-9]*\).*/\1/p'
}
for n in 2000 6000; do
  "$BSC" run "${COMMON[@]}" --world "$OUT/world.so" --world-output /dev/null \
    --cycles $n --record "$OUT/rec$n.jsonl" "$PAPER/Behavior.bs"
  run_i[$n]=$(instructions "$BSC" run "${COMMON[@]}" --world "$OUT/world.so" \
    --world-output /dev/null --cycles $n "$PAPER/Behavior.bs")
  replay_i[$n]=$(instructions "$BSC" run "${COMMON[@]}" --replay "$OUT/rec$n.jsonl" "$PAPER/Behavior.bs")
done
awk -v r="$(( (replay_i[6000] - replay_i[2000]) / 4000 ))" \
    -v w="$(( (run_i[6000] - run_i[2000]) / 4000 ))" \
    'BEGIN { printf "instructions per cycle: replay %d, run %d (%.1fx)\n", r, w, r / w }'
