#!/usr/bin/env bash
# The performance benchmarks, each against a reference measured in the same
# run. Instructions are counted by valgrind's callgrind (not seconds), so
# the shared machines' noise does not matter.
#
# 1. The shared benchmark (../shared/bench, ported in bench/shared): the
#    "soccer" and "wide" behaviors compiled by bsc against the hand-written
#    protothreads of proto.cpp, both linked with the same harness.h, for i586
#    (-march=geode) and x86_64. Checks the checksums at -O0 to -O3, then
#    prints instructions per behavior cycle (callgrind, --toggle-collect on
#    the harness's bsc_cycle_*), state bytes, heap allocations per cycle and
#    the ratios bsc / protothreads; and bsc's -O0 instructions per cycle.
# 2. Tracing on the robot: the same i586 -O2 programs with the behavior
#    compiled with --instrument, which writes a trace record each cycle
#    (and, second figure, the cycle's record copied into a log ring).
# 3. Steps.bs, a parent task driving a child state machine, against the same
#    state machines written in C (steps_reference.c).
# 4. The cycle budget: the -O2 programs with the behavior compiled with
#    --cycle-budget (a charge per loop pass; never running out here).
# 5. Assertions: soccer.bs's four `assert`s (which hold) compiled with
#    --assertions=count and trap, against the default (left out).
# 6. The flight recorder: the -O2 programs with the behavior compiled with
#    --flight-recorder and each cycle recorded, with the log's bytes per
#    cycle.
#
#   bench/run.sh [BUILD_DIR]        (default: build)
#   BENCH_CYCLES=N                  cycles per callgrind run (default 100000)
set -euo pipefail
cd "$(dirname "$0")"
HERE=$PWD
BUILD=$(cd "${1:-../build}" && pwd)
BSC=$BUILD/bin/bsc
SHARED=$(cd ../../shared/bench 2>/dev/null && pwd) ||
  { echo "bench: ../shared/bench (the shared benchmark) is missing" >&2; exit 1; }
CYCLES=${BENCH_CYCLES:-100000}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
command -v valgrind >/dev/null || { echo "bench: valgrind is needed (apt-get install valgrind)" >&2; exit 1; }

# Compiler flags of the shared README's reference build, per target.
CXX=clang++-19
declare -A CXXFLAGS=([i586]="--target=i586-linux-gnu -march=geode" [x86_64]="")

build_reference() { # target
  $CXX ${CXXFLAGS[$1]} -std=c++20 -O2 -o "$OUT/proto-$1" "$SHARED/proto.cpp"
}

build_bsc() { # target behavior opt -> $OUT/bsc-target-behavior-opt
  shared/build.sh "$BUILD" "$SHARED" "$1" "$2" "$3" "$OUT/$1-$2$3"
  cp "$OUT/$1-$2$3/$2" "$OUT/bsc-$1-$2$3"
}

field() { # name line -> value of name=value in the harness's line
  grep -Eo "(^| )$1=[^ ]+" <<<"$2" | cut -d= -f2
}

# Instructions inside bsc_cycle_* per cycle, over $CYCLES closed-loop cycles.
per_cycle() { # program behavior
  valgrind --tool=callgrind --callgrind-out-file="$OUT/cg.out" \
    --toggle-collect='bsc_cycle_*' "$1" "$2" count "$CYCLES" >/dev/null 2>"$OUT/cg.err"
  local total
  total=$(grep -Eo 'Collected : [0-9]+' "$OUT/cg.err" | grep -Eo '[0-9]+')
  awk -v t="$total" -v n="$CYCLES" 'BEGIN { printf "%.1f", t / n }'
}

status=0
echo "== shared benchmark ($CYCLES cycles; instructions per behavior cycle)"
printf '%-7s %-7s %10s %10s %6s %12s %10s\n' behavior target protothr bsc-O2 ratio state-bytes heap/cycle
for t in i586 x86_64; do
  build_reference "$t"
  for b in soccer wide; do
    ref=$("$OUT/proto-$t" "$b" verify)
    for o in -O0 -O1 -O2 -O3; do
      build_bsc "$t" "$b" "$o"
      got=$("$OUT/bsc-$t-$b$o" "$b" verify)
      if [[ $(field checksum "$got") != $(field checksum "$ref") ]]; then
        echo "bench: $b $t $o: checksum $(field checksum "$got"), protothreads $(field checksum "$ref")" >&2
        status=1
      fi
    done
    p=$(per_cycle "$OUT/proto-$t" "$b")
    c=$(per_cycle "$OUT/bsc-$t-$b-O2" "$b")
    printf '%-7s %-7s %10s %10s %6s %12s %10s\n' "$b" "$t" "$p" "$c" \
      "$(awk -v a="$c" -v b="$p" 'BEGIN { printf "%.2f", a / b }')" \
      "$(field state_bytes "$ref")/$(field state_bytes "$got")" \
      "$(field allocs_per_cycle "$got")"
  done
done
((status == 0)) && echo "checksums: bsc at -O0 to -O3 equals the protothreads on both targets"

echo "== bsc -O0 (instructions per behavior cycle; issue 11: nothing gets slower at -O0)"
for t in i586 x86_64; do
  for b in soccer wide; do
    echo "$b $t: $(per_cycle "$OUT/bsc-$t-$b-O0" "$b")"
  done
done

echo "== tracing on the robot (i586 -O2, --instrument: each task call writes the state's trace record)"
pct() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%+.1f%%", (b - a) / a * 100 }'; }
for b in soccer wide; do
  shared/build.sh "$BUILD" "$SHARED" i586 "$b" -O2 "$OUT/trace-$b" -DBENCH_TRACE
  shared/build.sh "$BUILD" "$SHARED" i586 "$b" -O2 "$OUT/log-$b" -DBENCH_TRACE -DBENCH_TRACE_LOG
  ref=$(field checksum "$("$OUT/proto-i586" "$b" verify)")
  for v in trace log; do
    got=$("$OUT/$v-$b/$b" "$b" verify)
    if [[ $(field checksum "$got") != "$ref" ]]; then
      echo "bench: $b with --instrument ($v): checksum $(field checksum "$got"), protothreads $ref" >&2
      status=1
    fi
  done
  plain=$(per_cycle "$OUT/bsc-i586-$b-O2" "$b")
  traced=$(per_cycle "$OUT/trace-$b/$b" "$b")
  logged=$(per_cycle "$OUT/log-$b/$b" "$b")
  echo "$b: $plain -> $traced instructions per cycle with the record ($(pct "$plain" "$traced"); issue 10's budget: +10%), $logged with a copy of it into a log ring ($(pct "$plain" "$logged")); state bytes $(field state_bytes "$got")"
done

echo "== the flight recorder (-O2, --flight-recorder: each cycle's input changes and output changes into 16 KiB blocks; docs/repl.md \"The robot's log\")"
for t in i586 x86_64; do
  for b in soccer wide; do
    shared/build.sh "$BUILD" "$SHARED" "$t" "$b" -O2 "$OUT/flight-$t-$b" -DBENCH_FLIGHT
    ref=$(field checksum "$("$OUT/proto-$t" "$b" verify)")
    got=$("$OUT/flight-$t-$b/$b" "$b" verify 2>/dev/null)
    if [[ $(field checksum "$got") != "$ref" ]]; then
      echo "bench: $b $t with --flight-recorder: checksum $(field checksum "$got"), protothreads $ref" >&2
      status=1
    fi
    plain=$(per_cycle "$OUT/bsc-$t-$b-O2" "$b")
    flight=$(per_cycle "$OUT/flight-$t-$b/$b" "$b")
    bytes=$("$OUT/flight-$t-$b/$b" "$b" count "$CYCLES" 2>&1 >/dev/null |
      awk '/^flight:/ { printf "%.1f", $2 / $5 }')
    echo "$b $t: $plain -> $flight instructions per cycle (+$(awk -v a="$plain" -v b="$flight" 'BEGIN { printf "%.0f", b - a }'), $(pct "$plain" "$flight")), $bytes log bytes per cycle"
  done
done

echo "== the cycle budget (-O2, --cycle-budget=1000000: a load, compare and store per loop pass)"
for t in i586 x86_64; do
  for b in soccer wide; do
    shared/build.sh "$BUILD" "$SHARED" "$t" "$b" -O2 "$OUT/budget-$t-$b" -DBENCH_BUDGET
    ref=$(field checksum "$("$OUT/proto-$t" "$b" verify)")
    got=$("$OUT/budget-$t-$b/$b" "$b" verify)
    if [[ $(field checksum "$got") != "$ref" ]]; then
      echo "bench: $b $t with --cycle-budget: checksum $(field checksum "$got"), protothreads $ref" >&2
      status=1
    fi
    plain=$(per_cycle "$OUT/bsc-$t-$b-O2" "$b")
    budget=$(per_cycle "$OUT/budget-$t-$b/$b" "$b")
    echo "$b $t: $plain -> $budget instructions per cycle ($(pct "$plain" "$budget")); state bytes $(field state_bytes "$got")"
  done
done

echo "== assertions (soccer -O2; the default leaves soccer.bs's 4 assertions out)"
for t in i586 x86_64; do
  plain=$(per_cycle "$OUT/bsc-$t-soccer-O2" soccer)
  line="soccer $t: none $plain"
  for m in COUNT TRAP; do
    shared/build.sh "$BUILD" "$SHARED" "$t" soccer -O2 "$OUT/assert-$m-$t" "-DBENCH_ASSERT_$m"
    ref=$(field checksum "$("$OUT/proto-$t" soccer verify)")
    got=$("$OUT/assert-$m-$t/soccer" soccer verify)
    if [[ $(field checksum "$got") != "$ref" ]]; then
      echo "bench: soccer $t with --assertions=${m,,}: checksum $(field checksum "$got"), protothreads $ref" >&2
      status=1
    fi
    n=$(per_cycle "$OUT/assert-$m-$t/soccer" soccer)
    line+=", ${m,,} $n ($(pct "$plain" "$n"))"
    [[ $m == COUNT ]] && count_bytes=$(field state_bytes "$got")
  done
  echo "$line instructions per cycle; state bytes with count $count_bytes"
done

echo "== Steps.bs against hand-written C (host)"
N1=10000 N2=60000
instructions() { # program args... -> total instructions executed
  valgrind --tool=callgrind --callgrind-out-file="$OUT/cg.out" "$@" >/dev/null 2>"$OUT/cg.err"
  grep -Eo 'Collected : [0-9]+' "$OUT/cg.err" | grep -Eo '[0-9]+'
}
steps_per_cycle() { # a b -> per-cycle instructions
  awk -v a="$1" -v b="$2" -v n1=$N1 -v n2=$N2 'BEGIN { printf "%.2f", (b - a) / (n2 - n1) }'
}
"$BSC" -O2 --cycles $N1 Steps.bs -o "$OUT/bs1"
"$BSC" -O2 --cycles $N2 Steps.bs -o "$OUT/bs2"
cc -O2 steps_reference.c -o "$OUT/ref"
bs=$(steps_per_cycle "$(instructions "$OUT/bs1")" "$(instructions "$OUT/bs2")")
ref=$(steps_per_cycle "$(instructions "$OUT/ref" $N1)" "$(instructions "$OUT/ref" $N2)")
echo "instructions per cycle: bsc $bs, hand-written C $ref"
echo "ratio bsc / C: $(awk -v a="$bs" -v b="$ref" 'BEGIN { printf "%.2f", a / b }')"
exit $status
