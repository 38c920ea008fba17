#!/usr/bin/env bash
# The debugging side's budgets (issue 10), measured in one run:
#  - `:reload` of a generated 2,700-line behavior (bench/gen-behavior.py):
#    the time of a REPL session that reloads once, less the same session
#    without the reload; best of 5, on one core.
#  - 10,000 cycles of the paper's soccer behavior stepped in the REPL
#    (`:step 10000`, printing each cycle's output changes, and `:run 10000`),
#    less a session that steps once; best of 5, on one core.
#  - time travel (issue 26) over 100,000 cycles of the paper's soccer
#    behavior driven by a world library (examples/soccer/world_library.cpp around
#    examples/soccer's world): `:run 100000` against `bsc run --cycles
#    100000` of the same world (the cost of keeping the history), then
#    `:goto 50000` from the end, `:goto 99999`, `:history output.motion`
#    over all cycles, each less the session without it; peak memory of the
#    session with the 100,000 cycles against one with 1.
#  - the boundary to registered C++ (issue 38) both ways: the same with the
#    soccer bindings' math kept (built with -DSOCCER_KEEP_MATH: every call
#    of norm, the operators and fabs is recorded) against registered
#    `.pure()` (the default: only constructors and properties are kept),
#    and the bytes the history keeps per cycle.
# (Tracing on the robot, `--instrument`, is counted by bench/run.sh on the
# shared benchmark's behaviors for i586.)
#   bench/repl.sh [BUILD_DIR]     (default: build)
set -euo pipefail
cd "$(dirname "$0")"
BUILD=$(cd "${1:-../build}" && pwd)
BSC=$BUILD/bin/bsc
PAPER=../../shared/conformance/paper
SOCCER_O=$BUILD/test/bind-objects/SoccerBindings.host.o
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
command -v valgrind >/dev/null || { echo "bench: valgrind is needed (apt-get install valgrind)" >&2; exit 1; }
PIN=()
command -v taskset >/dev/null && PIN=(taskset -c 0)

# seconds BATCH ARGS...: the best wall time of five REPL sessions.
seconds() {
  local batch=$1; shift
  python3 - "$batch" "${PIN[@]}" "$BSC" repl "$@" <<'PY'
import subprocess, sys, time
batch, cmd = sys.argv[1], sys.argv[2:]
best = None
for _ in range(5):
    with open(batch) as f:
        t = time.perf_counter()
        subprocess.run(cmd, stdin=f, stdout=subprocess.DEVNULL, check=True)
        t = time.perf_counter() - t
    best = t if best is None else min(best, t)
print("%.4f" % best)
PY
}
# peak_mb BATCH ARGS...: the peak resident memory of a REPL session (MB).
peak_mb() {
  local batch=$1; shift
  python3 - "$batch" "$BSC" repl "$@" <<'PY'
import resource, subprocess, sys
batch, cmd = sys.argv[1], sys.argv[2:]
with open(batch) as f:
    subprocess.run(cmd, stdin=f, stdout=subprocess.DEVNULL, check=True)
print("%.1f" % (resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024))
PY
}
diff_s() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.3f", a - b }'; }

python3 gen-behavior.py 100 > "$OUT/Big.bs"
printf ':step 3\n' > "$OUT/base.txt"
printf ':step 3\n:reload\n' > "$OUT/reload.txt"
base=$(seconds "$OUT/base.txt" "$OUT/Big.bs")
reload=$(seconds "$OUT/reload.txt" "$OUT/Big.bs")
echo "reload of a $(wc -l < "$OUT/Big.bs")-line behavior: $(diff_s "$reload" "$base") s (goal < 0.3 s; load and first cycles $base s)"

E=(--bind "$SOCCER_O" -I "$PAPER" --entry Behavior::gotoBallAndKick "$PAPER/Behavior.bs")
printf ':step\n' > "$OUT/one.txt"
printf ':step 10000\n' > "$OUT/step.txt"
printf ':run 10000\n' > "$OUT/run.txt"
one=$(seconds "$OUT/one.txt" "${E[@]}")
step=$(seconds "$OUT/step.txt" "${E[@]}")
run=$(seconds "$OUT/run.txt" "${E[@]}")
echo "10,000 cycles of the paper's soccer behavior: :step $(diff_s "$step" "$one") s, :run $(diff_s "$run" "$one") s (goal < 0.3 s)"

# Time travel over 100,000 cycles with a world.
g++ -std=c++20 -O2 -fPIC -shared -I../examples/soccer -I/usr/include/eigen3 \
  ../examples/soccer/world_library.cpp ../examples/soccer/SoccerWorld.cpp -o "$OUT/world.so"
W=(--world "$OUT/world.so" "${E[@]}")
printf ':run 100000\n' > "$OUT/run100k.txt"
{ echo ':run 100000'; for _ in $(seq 1000); do echo ':goto 50000'; echo ':goto 99999'; done; } > "$OUT/goto.txt"
printf ':run 100000\n:history output.motion\n' > "$OUT/history.txt"
printf ':run 1\n' > "$OUT/run1.txt"
# run_seconds CYCLES: the best wall time of five `bsc run`s with the world.
run_seconds() {
  python3 best_time.py 5 "${PIN[@]}" "$BSC" run --cycles "$1" "${W[@]}"
}
live=$(diff_s "$(run_seconds 100000)" "$(run_seconds 1)")
one=$(seconds "$OUT/run1.txt" "${W[@]}")
run100k=$(seconds "$OUT/run100k.txt" "${W[@]}")
goto=$(seconds "$OUT/goto.txt" "${W[@]}")
history=$(seconds "$OUT/history.txt" "${W[@]}")
echo "100,000 cycles with a world, less 1: bsc run $live s, the REPL's :run (keeping the history) $(diff_s "$run100k" "$one") s"
echo "  :goto 50000 and :goto 99999 from there, 1,000 times each: $(awk -v a="$goto" -v b="$run100k" 'BEGIN { printf "%.2f", (a - b) * 1000 / 2000 }') ms per :goto"
echo "  :history output.motion over the 100,000 cycles: $(diff_s "$history" "$run100k") s"
echo "  peak memory: $(peak_mb "$OUT/run100k.txt" "${W[@]}") MB after 100,000 cycles, $(peak_mb "$OUT/run1.txt" "${W[@]}") MB after 1"

# The boundary both ways: the math registered pure (above) or kept.
g++ -std=c++20 -O2 -DSOCCER_KEEP_MATH -I../include -I/usr/include/eigen3 \
  -c ../examples/soccer/SoccerBindings.cpp -o "$OUT/SoccerKeep.o"
K=(--world "$OUT/world.so" --bind "$OUT/SoccerKeep.o" -I "$PAPER" --entry Behavior::gotoBallAndKick "$PAPER/Behavior.bs")
one_k=$(seconds "$OUT/run1.txt" "${K[@]}")
run100k_k=$(seconds "$OUT/run100k.txt" "${K[@]}")
goto_k=$(seconds "$OUT/goto.txt" "${K[@]}")
peak1=$(peak_mb "$OUT/run1.txt" "${W[@]}"); peak=$(peak_mb "$OUT/run100k.txt" "${W[@]}")
peak1_k=$(peak_mb "$OUT/run1.txt" "${K[@]}"); peak_k=$(peak_mb "$OUT/run100k.txt" "${K[@]}")
per_cycle() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.0f", (a - b) * 1048576 / 100000 }'; }
echo "the boundary to C++ over 100,000 cycles (:run, :goto, peak memory less 1 cycle's, per cycle):"
echo "  math pure: :run $(diff_s "$run100k" "$one") s, $(awk -v a="$goto" -v b="$run100k" 'BEGIN { printf "%.2f", (a - b) * 1000 / 2000 }') ms per :goto, $(per_cycle "$peak" "$peak1") bytes per cycle"
echo "  math kept: :run $(diff_s "$run100k_k" "$one_k") s, $(awk -v a="$goto_k" -v b="$run100k_k" 'BEGIN { printf "%.2f", (a - b) * 1000 / 2000 }') ms per :goto, $(per_cycle "$peak_k" "$peak1_k") bytes per cycle"

# examples/team (one robot, so that the REPL keeps a history): no calls into
# C++ but the team world's end hook, which the history keeps as a call.
TEAM=../examples/team
g++ -std=c++20 -O2 -I../include -c "$TEAM/bindings.cpp" -o "$OUT/team.o"
g++ -std=c++20 -O2 -fPIC -shared -I../include "$TEAM/world.cpp" -o "$OUT/team.so"
T=(--bind "$OUT/team.o" --world "$OUT/team.so" --robots 1 --entry Players::play "$TEAM/Players.bs")
team_live=$(diff_s "$(python3 best_time.py 5 "${PIN[@]}" "$BSC" run --cycles 100000 "${T[@]}")" \
                   "$(python3 best_time.py 5 "${PIN[@]}" "$BSC" run --cycles 1 "${T[@]}")")
team_one=$(seconds "$OUT/run1.txt" "${T[@]}")
team_run=$(seconds "$OUT/run100k.txt" "${T[@]}")
team_peak1=$(peak_mb "$OUT/run1.txt" "${T[@]}"); team_peak=$(peak_mb "$OUT/run100k.txt" "${T[@]}")
echo "  examples/team, one robot: bsc run $team_live s, :run $(diff_s "$team_run" "$team_one") s, $(per_cycle "$team_peak" "$team_peak1") bytes per cycle"
