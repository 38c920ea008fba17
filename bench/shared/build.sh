#!/usr/bin/env bash
# Builds the shared benchmark's harness (../../../shared/bench/harness.h)
# around one behavior compiled by bsc: bench/run.sh and
# test/Run/shared-bench.test use it.
#   build.sh BSC_BUILD_DIR SHARED_BENCH_DIR i586|x86_64 soccer|wide -O<n> OUT
#            [-DBENCH_TRACE [-DBENCH_TRACE_LOG]] [-DBENCH_BUDGET]
#            [-DBENCH_ASSERT_COUNT | -DBENCH_ASSERT_TRAP] [-DBENCH_FLIGHT]
# (-DBENCH_TRACE: the behavior compiled with --instrument, its trace record
# started each cycle; -DBENCH_TRACE_LOG: and copied into a log;
# -DBENCH_BUDGET: compiled with --cycle-budget=1000000, which it never
# runs out of; -DBENCH_ASSERT_COUNT, -DBENCH_ASSERT_TRAP: compiled with
# --assertions=count or trap, for soccer.bs's assertions, which hold;
# -DBENCH_FLIGHT: compiled with --flight-recorder, each cycle recorded.)
# writes OUT/<behavior> (and its objects beside it).
set -euo pipefail
build=$1 shared=$2 target=$3 behavior=$4 opt=$5 out=$6
shift 6 # the rest: flags for the glue
here=$(cd "$(dirname "$0")" && pwd)
include=$(cd "$here/../../include" && pwd)
case $target in
  i586) cxxflags=(--target=i586-linux-gnu -march=geode) rt=libbscript_rt_i586.a ;;
  x86_64) cxxflags=() rt=libbscript_rt.a ;;
  *) echo "build.sh: unknown target '$target'" >&2; exit 2 ;;
esac
glue=("$@")
[[ $behavior == wide ]] && glue+=(-DBENCH_WIDE)
instrument=()
[[ " ${glue[*]} " == *" -DBENCH_TRACE "* ]] && instrument=(--instrument)
[[ " ${glue[*]} " == *" -DBENCH_BUDGET "* ]] && instrument+=(--cycle-budget=1000000)
[[ " ${glue[*]} " == *" -DBENCH_ASSERT_COUNT "* ]] && instrument+=(--assertions=count)
[[ " ${glue[*]} " == *" -DBENCH_ASSERT_TRAP "* ]] && instrument+=(--assertions=trap)
[[ " ${glue[*]} " == *" -DBENCH_FLIGHT "* ]] && instrument+=(--flight-recorder)
cxx=(clang++-19 "${cxxflags[@]}" -std=c++20 -O2 -I "$include" -I "$shared")
mkdir -p "$out"
"${cxx[@]}" -c "$here/BenchBindings.cpp" -o "$out/bind.o"
args=(-target "$target" --bind "$out/bind.o" --behavior-name bench -I "$here"
      "${instrument[@]}" "$here/$behavior.bs")
"$build/bin/bsc" "$opt" -c "${args[@]}" -o "$out/behavior.o"
"$build/bin/bsc" --emit-header "${args[@]}" -o "$out/behavior.h"
"${cxx[@]}" "${glue[@]}" -I "$out" -c "$here/bench_bsc.cpp" -o "$out/glue.o"
clang++-19 "${cxxflags[@]}" "$out/glue.o" "$out/behavior.o" "$out/bind.o" \
  "$build/lib/$rt" -o "$out/$behavior"
