#!/usr/bin/env bash
# Builds and runs the closed-loop soccer demo (host.cpp) for one target;
# run-i586 and run-host call this. See run-i586 for the environment.
#
# usage: build-run.sh i586|x86_64 [Behavior|Kick]
set -euo pipefail

target=$1
module=${2:-Behavior}
here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../.." && pwd)
paper=${SOCCER_PAPER:-$repo/../shared/conformance/paper}
bsc=${BSC:-$repo/build/bin/bsc}
libdir=${BSC_LIBDIR:-$repo/build/lib}
cxx=${CXX:-g++}
out=${SOCCER_OUT:-}
if [ -z "$out" ]; then
  out=$(mktemp -d)
  trap 'rm -rf "$out"' EXIT
fi
mkdir -p "$out"

case $target in
  i586)
    cflags=(-m32 -march=i586 -mtune=geode -fPIC)
    bscflags=(-target i586)
    rt=$libdir/libbscript_rt_i586.a
    run=(python3 "$repo/utils/run-i586")
    ;;
  x86_64)
    cflags=()
    bscflags=(-target x86_64)
    rt=$libdir/libbscript_rt.a
    run=()
    ;;
  *)
    echo "build-run.sh: unknown target '$target' (i586 or x86_64)" >&2
    exit 2
    ;;
esac
cxxflags=(-std=c++20 "${cflags[@]}" -O2 -Wall -I "$repo/include"
          -I /usr/include/eigen3 -I "$here")

"$cxx" "${cxxflags[@]}" -c "$here/SoccerWorld.cpp" -o "$out/SoccerWorld.o"

if [ -n "${SOCCER_STUB:-}" ]; then
  # The hand-written stand-in for the behavior (stub/behavior.h): tests the
  # world and the host without the compiler.
  "$cxx" "${cxxflags[@]}" -I "$here/stub" -DSOCCER_MODULE="$module" \
    -c "$here/host.cpp" -o "$out/host.o"
  "$cxx" "${cflags[@]}" "$out/host.o" "$out/SoccerWorld.o" -o "$out/soccer"
else
  # The bindings: the same object is read by bsc and linked.
  "$cxx" "${cxxflags[@]}" -c "$here/SoccerBindings.cpp" -o "$out/SoccerBindings.o"
  # The paper's files, unchanged.
  bsc_args=("${bscflags[@]}" --bind "$out/SoccerBindings.o" -I "$paper"
            --behavior-name soccer "$paper/$module.bs")
  # $SOCCER_FLIGHT_LOG: the robot's flight log goes there (host.cpp).
  flight=() hostflags=()
  if [ -n "${SOCCER_FLIGHT_LOG:-}" ]; then
    flight=(--flight-recorder) hostflags=(-DSOCCER_FLIGHT)
  fi
  "$bsc" -O2 -c "${flight[@]}" "${bsc_args[@]}" -o "$out/behavior.o"
  "$bsc" --emit-header "${flight[@]}" "${bsc_args[@]}" -o "$out/behavior.h"
  "$cxx" "${cxxflags[@]}" "${hostflags[@]}" -I "$out" -DSOCCER_MODULE="$module" \
    -c "$here/host.cpp" -o "$out/host.o"
  "$cxx" "${cflags[@]}" "$out/host.o" "$out/SoccerWorld.o" \
    "$out/behavior.o" "$out/SoccerBindings.o" "$rt" -o "$out/soccer"
fi

"${run[@]}" "$out/soccer"
