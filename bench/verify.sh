#!/usr/bin/env bash
# `bsc verify`'s budgets (issue 42), on one core (taskset where there is
# one), each figure with its target:
#  - soccer: the paper's soccer behavior (../shared/conformance/paper,
#    unchanged) under bench/verify/Striker.bs's assumptions and assertions,
#    with bench/verify/MathModels.bs's models of its C++ math: verified for
#    30 cycles (goal < 60 s);
#  - lock: bench/verify/Lock.bs, a button-press task with a planted bug
#    that only one sequence of six presses reaches: its counterexample
#    (goal < 10 s), replayed by `bsc run --replay` to the same failure;
#  - the peak memory of each (goal < 2 GB).
# Seconds, not instructions: the solver's time is what a user waits for;
# best of 3 runs.
#   bench/verify.sh [BUILD_DIR]     (default: build)
set -euo pipefail
cd "$(dirname "$0")"
BUILD=$(cd "${1:-../build}" && pwd)
BSC=$BUILD/bin/bsc
PAPER=$(cd ../../shared/conformance/paper && pwd)
SOCCER_O=$BUILD/test/bind-objects/SoccerBindings.host.o
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
g++ -std=c++20 -O2 -I../include -c ../test/REPL/Inputs/boundary/sim.cpp -o "$OUT/sim.o"
ONE_CORE=()
command -v taskset >/dev/null && ONE_CORE=(taskset -c 0)

# run NAME CMD...: the best wall time and the largest peak memory of three
# runs of CMD (its exit status is kept in $OUT/NAME.status), its output in
# $OUT/NAME.out.
run() {
  local name=$1
  shift
  for i in 1 2 3; do
    set +e
    /usr/bin/time -f "%e %M" -o "$OUT/$name.time.$i" "${ONE_CORE[@]}" "$@" > "$OUT/$name.out" 2>&1
    echo $? > "$OUT/$name.status"
    set -e
  done
  for i in 1 2 3; do tail -1 "$OUT/$name.time.$i"; done | awk '{ if (best == "" || $1 < best) best = $1; if ($2 > mem) mem = $2 }
    END { printf "%.2f s, peak %.0f MB", best, mem / 1024 }'
}

soccer=$(run soccer "$BSC" verify --bind "$SOCCER_O" -I "$PAPER" --entry Striker::play \
  --cycles 30 --model verify/MathModels.bs verify/Striker.bs)
grep -q '^verified: 3 assertions hold' "$OUT/soccer.out" ||
  { echo "bench: the soccer behavior was not verified:" >&2; cat "$OUT/soccer.out" >&2; exit 1; }
echo "soccer, 30 cycles: $soccer (goal < 60 s, < 2048 MB)"
sed 's/^/  /' "$OUT/soccer.out"

lock=$(run lock "$BSC" verify --bind "$OUT/sim.o" --entry lock --cycles 12 \
  -o "$OUT/lock.jsonl" verify/Lock.bs)
grep -q 'cycle 6: assertion can fail' "$OUT/lock.out" ||
  { echo "bench: the planted bug was not found:" >&2; cat "$OUT/lock.out" >&2; exit 1; }
echo "lock, 12 cycles, the planted bug: $lock (goal < 10 s, < 2048 MB)"
grep -E 'counterexample:|cycle [0-9]: input' "$OUT/lock.out" | sed 's/^/  /'
"$BSC" run --bind "$OUT/sim.o" --entry lock --replay "$OUT/lock.jsonl" verify/Lock.bs \
  > "$OUT/replay.out" 2>&1 || true
if grep -q 'cycle 6: assertion failed' "$OUT/replay.out"; then
  echo "  replayed by bsc run --replay: the same assertion fails in cycle 6"
else
  echo "bench: the counterexample does not replay to the same failure" >&2
  exit 1
fi
