#!/usr/bin/env bash
# The debugging side's budgets (issue 10), measured in one run:
#  - `:reload` of a generated 2,700-line behavior (bench/gen-behavior.py):
#    the time of a REPL session that reloads once, less the same session
#    without the reload; best of 5, on one core.
#  - 10,000 cycles of the paper's soccer behavior stepped in the REPL
#    (`:step 10000`, printing each cycle's output changes, and `:run 10000`),
#    less a session that steps once; best of 5, on one core.
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
