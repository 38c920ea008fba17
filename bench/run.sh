#!/usr/bin/env bash
# Instructions per behavior cycle: bsc's code for Steps.bs against the same
# state machines hand-written in C (steps_reference.c), both at -O2 on the
# host, counted by valgrind's callgrind (instruction counts, not seconds, so
# the shared machines' noise does not matter). Start-up cost cancels out:
# each program runs at two cycle counts and the difference is divided by the
# difference in cycles.
#   bench/run.sh [BUILD_DIR]     (default: build)
set -euo pipefail
cd "$(dirname "$0")"
BUILD=${1:-../build}
BSC=$BUILD/bin/bsc
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
command -v valgrind >/dev/null || { echo "bench: valgrind is needed (apt-get install valgrind)" >&2; exit 1; }

N1=10000 N2=60000
instructions() { # program args... -> total instructions executed
  valgrind --tool=callgrind --callgrind-out-file="$OUT/cg.out" "$@" >/dev/null 2>"$OUT/cg.err"
  grep -Eo 'Collected : [0-9]+' "$OUT/cg.err" | grep -Eo '[0-9]+'
}
per_cycle() { # name a b -> per-cycle instructions
  awk -v a="$2" -v b="$3" -v n1=$N1 -v n2=$N2 'BEGIN { printf "%.2f", (b - a) / (n2 - n1) }'
}

"$BSC" -O2 --cycles $N1 Steps.bs -o "$OUT/bs1"
"$BSC" -O2 --cycles $N2 Steps.bs -o "$OUT/bs2"
cc -O2 steps_reference.c -o "$OUT/ref"

bs=$(per_cycle bs "$(instructions "$OUT/bs1")" "$(instructions "$OUT/bs2")")
ref=$(per_cycle ref "$(instructions "$OUT/ref" $N1)" "$(instructions "$OUT/ref" $N2)")
echo "instructions per cycle: bsc $bs, hand-written C $ref"
echo "ratio bsc / C: $(awk -v a="$bs" -v b="$ref" 'BEGIN { printf "%.2f", a / b }')"
