#!/usr/bin/env bash
# The two quick-start commands of the README:
#   ./dev.sh demo   install what is missing, build, cross-build the paper's
#                   fib.bs for i586 and run it
#   ./dev.sh test   install what is missing, build, run the whole test suite
#   ./dev.sh sanitize  the same suite with bsc built with ASan and UBSan
#                   (in build-sanitize/)
#   ./dev.sh fuzz frontend|binding|jsonl|timeline|binarylog [SECONDS]
#                   a libFuzzer campaign on one target (fuzz/README.md)
# Both work on a fresh Debian 12 machine as root (apt), and are what CI runs.
set -euo pipefail
cd "$(dirname "$0")"
ROOT=$PWD
BUILD=${BSC_BUILD_DIR:-$ROOT/build}

# Debian packages the build, the tests and the examples need.
PACKAGES=(cmake ninja-build g++ gcc-multilib g++-multilib python3 file
          llvm-19-dev llvm-19-tools clang-19 lld-19 libgtest-dev
          libeigen3-dev libedit-dev zlib1g-dev libzstd-dev qemu-user gdb
          chromium fonts-dejavu-core  # chromium: the timeline page's tests
          neovim  # docs/editors.md's Neovim 0.7 recipe, run in the tests
          lcov  # genhtml reads the tracefiles of --coverage in the tests
          libz3-dev  # bsc verify: Z3, the solver LLVM 19 is built with
          nodejs)  # nodejs, npm: the VS Code extension's build and tests
# NodeSource's nodejs has npm inside, and apt refuses Debian's npm beside it.
command -v npm >/dev/null || PACKAGES+=(npm)

install_missing() {
  local missing=()
  for p in "${PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  ((${#missing[@]})) || return 0
  echo "dev.sh: installing ${missing[*]}"
  local sudo=()
  [[ $(id -u) == 0 ]] || sudo=(sudo)
  "${sudo[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
}

build() {
  cmake -S "$ROOT" -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$BUILD"
}

demo() {
  local out=$BUILD/demo
  mkdir -p "$out"
  local fib=$ROOT/../shared/conformance/paper/fib.bs
  echo "== bsc -target i586 $fib"
  "$BUILD/bin/bsc" -target i586 -O2 "$fib" -o "$out/fib-i586"
  file "$out/fib-i586"
  echo "== running the i586 program"
  "$ROOT/utils/run-i586" "$out/fib-i586" | tee "$out/fib.out"
  diff -u "$ROOT/../shared/conformance/paper/fib.expected" "$out/fib.out"
  echo "== output matches fib.expected"
}

run_tests() {
  local status=0
  # Results of an earlier run must not be counted if this one stops early.
  rm -f "$BUILD/ctest-results.xml" "$BUILD/lit-results.xml"
  ctest --test-dir "$BUILD" --output-on-failure -j"$(nproc)" \
        --output-junit "$BUILD/ctest-results.xml" || status=$?
  # One closing line with every unit test and every lit test counted.
  python3 "$ROOT/utils/summarize-tests.py" "$BUILD/ctest-results.xml" "$BUILD/lit-results.xml"
  return $status
}

# The whole suite against bsc built with ASan and UBSan. Leaks are not
# checked: LLVM keeps its registries to the end of the process.
sanitize() {
  BUILD=${BSC_BUILD_DIR:-$ROOT/build-sanitize}
  cmake -S "$ROOT" -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
        -DBSC_SANITIZE=ON >/dev/null
  cmake --build "$BUILD"
  ASAN_OPTIONS=detect_leaks=0:abort_on_error=0 \
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 run_tests
}

# A libFuzzer campaign (fuzz/README.md): a clang build with coverage and
# ASan in build-fuzz/, the corpus kept in build-fuzz/corpus-TARGET, seeded
# from the test suite, and crashing inputs written to build-fuzz/.
fuzz() {
  local target=${1:-} seconds=${2:-3600}
  [[ $target == frontend || $target == binding || $target == jsonl ||
     $target == timeline || $target == binarylog ]] ||
    { echo "usage: $0 fuzz frontend|binding|jsonl|timeline|binarylog [SECONDS]" >&2; exit 2; }
  PACKAGES+=(libclang-rt-19-dev)
  install_missing
  BUILD=${BSC_BUILD_DIR:-$ROOT/build-fuzz}
  CC=clang-19 CXX=clang++-19 cmake -S "$ROOT" -B "$BUILD" -G Ninja \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo -DBSC_FUZZ=ON >/dev/null
  local seeds=("$ROOT/fuzz/corpus/frontend" "$ROOT/test")
  if [[ $target == binding ]]; then
    cmake --build "$BUILD" --target bsc-fuzz-binding LitBindObjects BindTestObjects
    seeds=("$BUILD/test/bind-objects" "$BUILD/unittests/Bind/objects")
  elif [[ $target == jsonl ]]; then
    cmake --build "$BUILD" --target bsc-fuzz-jsonl
    seeds=("$ROOT/fuzz/corpus/jsonl")
  elif [[ $target == timeline ]]; then
    cmake --build "$BUILD" --target bsc-fuzz-timeline
    seeds=("$ROOT/fuzz/corpus/timeline")
  elif [[ $target == binarylog ]]; then
    cmake --build "$BUILD" --target bsc-fuzz-binarylog
    seeds=("$ROOT/fuzz/corpus/binarylog")
  else
    cmake --build "$BUILD" --target bsc-fuzz-frontend
  fi
  mkdir -p "$BUILD/corpus-$target"
  cd "$BUILD"
  ASAN_OPTIONS=detect_leaks=0 "$BUILD/bin/bsc-fuzz-$target" \
    -max_total_time="$seconds" -timeout=10 -rss_limit_mb=4096 \
    "$BUILD/corpus-$target" "${seeds[@]}"
}

case "${1:-}" in
  demo) install_missing; build; demo ;;
  test) install_missing; build; run_tests ;;
  sanitize) install_missing; sanitize ;;
  fuzz) shift; fuzz "$@" ;;
  *) echo "usage: $0 demo|test|sanitize|fuzz" >&2; exit 2 ;;
esac
