#!/usr/bin/env bash
# Configures (Release) and builds rangefill into build/ with as many jobs as there are cores: every
# target (the tests, benchmarks and Python module included; arguments are more cmake -D options),
# or only those named in RANGEFILL_TARGETS. RANGEFILL_WERROR=ON makes compiler warnings errors (CI).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release \
  -DRANGEFILL_BUILD_TESTS=ON -DRANGEFILL_BUILD_BENCHMARKS=ON -DRANGEFILL_BUILD_PYTHON=ON \
  -DRANGEFILL_BUILD_RESEARCH=ON -DRANGEFILL_WITH_PCL=ON \
  -DRANGEFILL_WERROR="${RANGEFILL_WERROR:-OFF}" "$@" >/dev/null
targets=()
for target in ${RANGEFILL_TARGETS:-}; do targets+=(--target "$target"); done
cmake --build "$root/build" -j "$(nproc)" "${targets[@]}"
