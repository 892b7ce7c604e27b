#!/usr/bin/env bash
# Runs the project's own benches and writes docs/results.md from their outputs.
#
# usage: scripts/results-page.sh [--meshes DIR] [--frames DIR] [--real-holes DIR]
#                                [--holes-per-mesh N] [--threads N] [--work DIR] [-o FILE]
#        scripts/results-page.sh --from DIR [-o FILE]
#
# The bundled sample (data/bunny-bottom.ply) is always used. The closed meshes, depth frames and
# open scans default to ../shared/data/{meshes,depth-real,real-holes} beside the repository; a
# directory that does not exist is skipped and the page says so. --holes-per-mesh (5) holes are
# punched into each closed mesh, --threads (every core) filled at once. Outputs go to --work
# (out/results by default), one file or directory per bench, with commands.tsv listing the exact
# command of each; -o is docs/results.md by default. --from DIR formats an existing work
# directory again without running anything. About two minutes on 2 cores.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
cd "$root"

meshes=../shared/data/meshes
frames=../shared/data/depth-real
real_holes=../shared/data/real-holes
holes_per_mesh=5
threads="$(nproc)"
work=out/results
output=docs/results.md
from=""
rangefill=build/bin/rangefill

while [ $# -gt 0 ]; do
  case "$1" in
    --meshes) meshes="$2"; shift 2 ;;
    --frames) frames="$2"; shift 2 ;;
    --real-holes) real_holes="$2"; shift 2 ;;
    --holes-per-mesh) holes_per_mesh="$2"; shift 2 ;;
    --threads) threads="$2"; shift 2 ;;
    --work) work="$2"; shift 2 ;;
    --from) from="$2"; shift 2 ;;
    -o|--output) output="$2"; shift 2 ;;
    -h|--help) sed -n '2,14p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "results-page.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done

if [ -n "$from" ]; then
  exec python3 scripts/results-page.py "$from" -o "$output"
fi

[ -x "$rangefill" ] || { echo "results-page.sh: $rangefill not found: build first (scripts/build.sh)" >&2; exit 3; }
rm -rf "$work"
mkdir -p "$work"
commands="$work/commands.tsv"
: >"$commands"

# run KEY STDOUT_FILE COMMAND...: runs COMMAND, its stdout to STDOUT_FILE ('-': none kept), and
# records KEY and the command line.
run() {
  local key="$1" out="$2"
  shift 2
  echo "results-page.sh: $*" >&2
  printf '%s\t%s\n' "$key" "$*" >>"$commands"
  if [ "$out" = - ]; then "$@" >/dev/null; else "$@" >"$out"; fi
}

printf 'version\t%s\n' "$("$rangefill" --version)" >"$work/about.tsv"
commit="$(git rev-parse --short HEAD 2>/dev/null || echo unknown)"
# Code changed since the last commit: the page says so.
git diff --quiet HEAD -- src include tools python CMakeLists.txt cmake 2>/dev/null ||
  commit="$commit with uncommitted changes to the code"
printf 'commit\t%s\n' "$commit" >>"$work/about.tsv"
printf 'built\t%s\n' "$(date -u -r "$rangefill" '+%Y-%m-%d %H:%M UTC')" >>"$work/about.tsv"
printf 'date\t%s\n' "$(date -u +%Y-%m-%d)" >>"$work/about.tsv"
printf 'cores\t%s\n' "$(nproc)" >>"$work/about.tsv"
printf 'cpu\t%s\n' "$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -1)" >>"$work/about.tsv"
for name in meshes frames real_holes; do
  printf 'data_%s\t%s\n' "$name" "${!name}" >>"$work/about.tsv"
done

# The bundled sample.
run holes-sample "$work/holes-sample.json" "$rangefill" holes data/bunny-bottom.ply --json
# repair exits 5 when it leaves a loop open; the sample's cut is a border, left open by design.
run repair-sample - "$rangefill" repair data/bunny-bottom.ply -o "$work/bunny-bottom-repaired.ply" \
  --report "$work/repair-sample.json" || [ $? -eq 5 ]
run info-sample "$work/info-sample.json" "$rangefill" info "$work/bunny-bottom-repaired.ply" --json
run depth-bench-sample - "$rangefill" depth-bench --meshes data/bunny-bottom.ply --views 4 \
  --csv "$work/depth-bench-sample.csv"

# The shared data, where present.
if [ -d "$real_holes" ]; then
  for mesh in "$real_holes"/*.ply; do
    name="$(basename "$mesh" .ply)"
    run "holes-real:$name" "$work/holes-real-$name.json" "$rangefill" holes "$mesh" --json
  done
fi
if [ -d "$meshes" ]; then
  bench=("$rangefill" bench --meshes "$meshes" --holes-per-mesh "$holes_per_mesh" --seed 1 --threads "$threads")
  run bench-default - "${bench[@]}" --inpainters telea --baselines cgal-fair,cgal-triangulate \
    --out "$work/bench-default"
  run bench-plane - "${bench[@]}" --filler plane --inpainters foe,ns,telea,mls,harmonic \
    --out "$work/bench-plane"
  run bench-trends - "${bench[@]}" --filler plane --inpainters telea --trends none,quadric,auto \
    --out "$work/bench-trends"
  run patch-bench "$work/patch-bench.json" "$rangefill" patch-bench --meshes "$meshes" --seed 2 \
    --inpainters foe,foe:roth-black,mls,harmonic,ns,telea --json
fi
if [ -d "$frames" ]; then
  # OpenCV contrib's solver prints its iterations on stdout: only the CSV is kept.
  run depth-bench-frames - "$rangefill" depth-bench --frames "$frames" --csv "$work/depth-bench-frames.csv"
fi

python3 scripts/results-page.py "$work" -o "$output"
echo "results-page.sh: wrote $output" >&2
