#!/usr/bin/env bash
# Fresh machine, one command: install what is missing, build, run the main job on the bundled sample.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/scripts/install-deps.sh"
"$root/scripts/build.sh"
"$root/build/bin/rangefill" holes "$root/data/bunny-bottom.ply"
