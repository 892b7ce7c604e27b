#!/usr/bin/env bash
# Builds the libFuzzer targets of tests/fuzz with clang into build-fuzz/ and runs each (the mesh
# readers and the depth images' decoders) for FUZZ_SECONDS (default 45) from the seed corpus
# tests/fuzz/corpus/<format>, two at a time.
# New inputs go to build-fuzz/corpus/, findings to build-fuzz/findings/<format>/; a finding fails.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="$root/build-fuzz"
seconds="${FUZZ_SECONDS:-45}"
"$root/scripts/install-deps.sh"
cmake -S "$root/tests/fuzz" -B "$build" -DCMAKE_CXX_COMPILER=clang++-14 >/dev/null
cmake --build "$build" -j "$(nproc)" >/dev/null

# Inputs of at most 16 KiB, 10 s each, no single allocation above 64 MiB (the readers allocate from
# what a file holds, never from what its header declares).
fuzz() {
  local format="$1"
  mkdir -p "$build/corpus/$format" "$build/findings/$format"
  "$build/fuzz_$format" "$build/corpus/$format" "$root/tests/fuzz/corpus/$format" \
    -dict="$root/tests/fuzz/$format.dict" -max_total_time="$seconds" -max_len=16384 -timeout=10 \
    -rss_limit_mb=2048 -malloc_limit_mb=64 -artifact_prefix="$build/findings/$format/" \
    -print_final_stats=1 >"$build/fuzz_$format.log" 2>&1
}

# Prints one line per fuzzer (runs, coverage) or its log when it found something.
report() {
  local format="$1" status="$2"
  if [ "$status" -ne 0 ]; then
    echo "fuzz: $format: FINDING (exit $status), see $build/findings/$format/"
    tail -n 40 "$build/fuzz_$format.log"
    return 1
  fi
  echo "fuzz: $format: $(grep -o 'stat::number_of_executed_units: [0-9]*' "$build/fuzz_$format.log" |
    grep -o '[0-9]*$') runs in ${seconds} s, $(grep -o 'cov: [0-9]*' "$build/fuzz_$format.log" |
    tail -n 1), no finding"
}

failed=0
for pair in "ply obj" "off stl" "image"; do
  pids=()
  for format in $pair; do
    fuzz "$format" &
    pids+=($!)
  done
  formats=($pair)
  for i in "${!pids[@]}"; do
    status=0
    wait "${pids[$i]}" || status=$?
    report "${formats[$i]}" "$status" || failed=1
  done
done
exit "$failed"
