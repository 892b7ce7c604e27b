#!/usr/bin/env bash
# Fresh machine, one command: install what the binary needs, build it (without the tests, the
# research sub-commands and point-cloud meshing: the test command builds those), repair the
# bundled sample scan into out/ with a picture of each repaired hole, and print what the result is.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/scripts/install-deps.sh" --demo
RANGEFILL_TARGETS=rangefill_cli "$root/scripts/build.sh" -DRANGEFILL_BUILD_TESTS=OFF \
  -DRANGEFILL_BUILD_BENCHMARKS=OFF -DRANGEFILL_BUILD_PYTHON=OFF -DRANGEFILL_BUILD_RESEARCH=OFF \
  -DRANGEFILL_WITH_PCL=OFF
mkdir -p "$root/out"
"$root/build/bin/rangefill" repair "$root/data/bunny-bottom.ply" -o "$root/out/bunny-bottom-repaired.ply" \
  --report "$root/out/bunny-bottom-report.json" --debug-dir "$root/out/bunny-bottom-holes"
"$root/build/bin/rangefill" info "$root/out/bunny-bottom-repaired.ply"
