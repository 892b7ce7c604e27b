#!/usr/bin/env bash
# Fresh machine, one command: install what is missing, build, repair the bundled sample scan.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/scripts/install-deps.sh"
"$root/scripts/build.sh"
mkdir -p "$root/out"
"$root/build/bin/rangefill" repair "$root/data/bunny-bottom.ply" -o "$root/out/bunny-bottom-repaired.ply" \
  --report "$root/out/bunny-bottom-report.json" --debug-dir "$root/out/bunny-bottom-images"
"$root/build/bin/rangefill" info "$root/out/bunny-bottom-repaired.ply"
