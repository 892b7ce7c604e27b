#!/usr/bin/env bash
# Builds the test suite and the rangefill binary with AddressSanitizer and UndefinedBehaviorSanitizer
# (RANGEFILL_SANITIZE) into build-sanitize/, without the benchmarks, and runs every test there.
# -O1: quicker to build than -O3, and the usual level for sanitizers.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="$root/build-sanitize"
"$root/scripts/install-deps.sh"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE=-O1 \
  -DRANGEFILL_SANITIZE=ON -DRANGEFILL_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build "$build" -j "$(nproc)"
cd "$build"
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 ctest --output-on-failure -j "$(nproc)"
