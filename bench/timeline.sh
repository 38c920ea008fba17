#!/usr/bin/env bash
# `bsc timeline`'s budgets (issue 27), measured in one run on two
# behaviors, each run 100,000 cycles in a closed loop with
# examples/soccer/world_library.cpp and recorded with `bsc run --record`:
#  - soccer: the paper's soccer behavior (Behavior.bs, Motion.bs, Head.bs;
#    4 to 6 tasks active per cycle);
#  - team: 9 files: the soccer behavior under a main task that also drives
#    five generated modules of bench/gen-behavior.py's units (each a parent
#    task whose child goes through three phases every few cycles): 42 tasks
#    active per cycle, a stress test of a large option tree.
# For each:
#  - `bsc timeline` of the recording: best of 3 wall times (goal < 2 s),
#    against the recording run itself (`bsc run --record`, best of 3);
#  - `bsc timeline --behavior` of the same run recorded as a binary log
#    (.bslog), which it replays: best of 3 (goal < 2 s);
#  - the page's size per 1,000 cycles, against the recording's;
#  - the page's first contentful paint and first full render in headless
#    Chromium (utils/browser.py --first-paint, median of 5 loads; goal
#    < 1 s).
#   bench/timeline.sh [BUILD_DIR]     (default: build)
set -euo pipefail
cd "$(dirname "$0")"
BUILD=$(cd "${1:-../build}" && pwd)
BSC=$BUILD/bin/bsc
PAPER=$(cd ../../shared/conformance/paper && pwd)
SOCCER_O=$BUILD/test/bind-objects/SoccerBindings.host.o
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
command -v chromium >/dev/null || { echo "bench: chromium is needed (./dev.sh installs it)" >&2; exit 1; }
CYCLES=100000

python3 - "$OUT" <<'PY'
import importlib.util, os, sys
out = sys.argv[1]
spec = importlib.util.spec_from_file_location("gen", "gen-behavior.py")
gen = importlib.util.module_from_spec(spec)
spec.loader.exec_module(gen)
for m in range(5):
    units = range(3 * m, 3 * m + 3)
    text = "".join(gen.UNIT.format(i=i) for i in units)
    text += "task run()\n    for(;; yield)\n"
    text += "".join("        parent%d()\n" % i for i in units)
    open(os.path.join(out, "Unit%d.bs" % m), "w").write(text)
main = ['requires "Behavior"\n'] + ['requires "Unit%d"\n' % m for m in range(5)]
main += ["\ntask main()\n    for(;; yield)\n        Behavior::gotoBallAndKick()\n"]
main += ["        Unit%d::run()\n" % m for m in range(5)]
open(os.path.join(out, "Team.bs"), "w").write("".join(main))
PY
g++ -std=c++20 -O2 -fPIC -shared -I../examples/soccer -I/usr/include/eigen3 \
  ../examples/soccer/world_library.cpp ../examples/soccer/SoccerWorld.cpp -o "$OUT/world.so"

# best CMD...: the best wall time of three runs of CMD.
best() { python3 best_time.py 3 "$@"; }
per_1000() { awk -v b="$(stat -c %s "$1")" -v n=$CYCLES 'BEGIN { printf "%.1f", b / 1024 / (n / 1000) }'; }

# measure NAME ENTRY FILE: the figures of one behavior.
measure() {
  local name=$1 entry=$2 file=$3
  local record timeline tasks
  record=$(best "$BSC" run --bind "$SOCCER_O" -I "$PAPER" -I "$OUT" --entry "$entry" \
    --world "$OUT/world.so" --world-output /dev/null --cycles $CYCLES \
    --record "$OUT/$name.jsonl" "$file")
  tasks=$(head -n 1000 "$OUT/$name.jsonl" | grep -o '"task":"[^"]*"' | sort -u | wc -l)
  timeline=$(best "$BSC" timeline "$OUT/$name.jsonl" -o "$OUT/$name.html")
  echo "$name: $tasks tasks, $CYCLES cycles"
  echo "  bsc timeline: $timeline s (goal < 2 s); recording the run: $record s (ratio $(awk -v a="$timeline" -v b="$record" 'BEGIN { printf "%.2f", a / b }'))"
  echo "  page: $(per_1000 "$OUT/$name.html") KiB per 1,000 cycles; the recording: $(per_1000 "$OUT/$name.jsonl") KiB per 1,000 cycles"
  # The same run as a binary log (docs/repl.md "The robot's log"), which
  # the timeline replays with the behavior.
  "$BSC" run --bind "$SOCCER_O" -I "$PAPER" -I "$OUT" --entry "$entry" \
    --world "$OUT/world.so" --world-output /dev/null --cycles $CYCLES \
    --record "$OUT/$name.bslog" "$file"
  # (Its note that the replay is exact, once per run, is not a figure.)
  binary=$(best bash -c '"$@" 2>/dev/null' _ "$BSC" timeline --behavior "$file" --bind "$SOCCER_O" \
    -I "$PAPER" -I "$OUT" --entry "$entry" "$OUT/$name.bslog" -o "$OUT/$name-bslog.html")
  echo "  bsc timeline of the binary log: $binary s (goal < 2 s); the log: $(per_1000 "$OUT/$name.bslog") KiB per 1,000 cycles"
  echo "  first paint (goal < 1 s):"
  python3 ../utils/browser.py --first-paint "$OUT/$name.html" | sed 's/^/    /'
  rm -f "$OUT/$name.jsonl"
}
measure soccer Behavior::gotoBallAndKick "$PAPER/Behavior.bs"
measure team Team::main "$OUT/Team.bs"
