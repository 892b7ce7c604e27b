#!/usr/bin/env bash
# Builds the test suite and the rangefill binary with AddressSanitizer and UndefinedBehaviorSanitizer
# (RANGEFILL_SANITIZE) into build-sanitize/, without the benchmarks, and runs the tests there.
# clang++-14 (installed for the fuzz stage): with both sanitizers it compiles our code faster than
# g++ 12 does, and its runtime is the reference one. -O1: the usual level for sanitizers; no -g
# (the reports name functions).
# Two tests are left to scripts/test.sh: evaluation-scale runs on ../shared whose code is covered
# here by smaller tests, and which take minutes under the sanitizers (RANGEFILL_SANITIZE_ALL=1 runs
# them as well): FillDepth.BeatsCvInpaintOnSensorFrames (every back-end on four VGA sensor frames)
# and Benchmark.PunchedSharedMeshesAreRepaired (60 holes in the shared meshes).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="$root/build-sanitize"
"$root/scripts/install-deps.sh"
cmake -S "$root" -B "$build" -DCMAKE_CXX_COMPILER=clang++-14 -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_CXX_FLAGS_RELEASE=-O1 -DRANGEFILL_SANITIZE=ON -DRANGEFILL_BUILD_BENCHMARKS=OFF \
  -DRANGEFILL_WERROR="${RANGEFILL_WERROR:-OFF}" >/dev/null
cmake --build "$build" -j "$(nproc)"
cd "$build"
exclude='^(FillDepth\.BeatsCvInpaintOnSensorFrames|Benchmark\.PunchedSharedMeshesAreRepaired)$'
[ "${RANGEFILL_SANITIZE_ALL:-0}" = 1 ] && exclude='^$'
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 ctest --output-on-failure -j "$(nproc)" \
  -E "$exclude"
