#!/usr/bin/env bash
# clang-tidy (the checks of .clang-tidy, every finding an error) on the C++ sources a change
# touched: the files changed since BASE (the first argument, default HEAD~1: the last commit)
# that the build compiles, through build/compile_commands.json (scripts/build.sh makes it). A
# changed header is checked through the sources of its folder that include it. Prints the files
# checked; exits non-zero on a finding.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
cd "$root"
base="${1:-HEAD~1}"
database="$root/build/compile_commands.json"
[ -f "$database" ] || { echo "tidy: $database is missing: run scripts/build.sh first" >&2; exit 2; }
if ! git rev-parse --verify -q "$base^{commit}" >/dev/null; then
  echo "tidy: no commit $base to compare with: nothing to check"
  exit 0
fi
mapfile -t changed < <(git diff --name-only --diff-filter=d "$base" -- '*.cpp' '*.h')
compiled() { grep -q "\"file\": \"$root/$1\"" "$database"; }
files=()
for file in "${changed[@]}"; do
  case "$file" in
    tests/fuzz/*) continue ;;  # a clang project of its own (scripts/fuzz.sh)
    *.cpp) compiled "$file" && files+=("$file") ;;
    *.h)  # the compiled sources that include it
      name="${file##*/}"
      while IFS= read -r source; do
        compiled "$source" && files+=("$source")
      done < <(git grep -l "#include \".*$name\"" -- '*.cpp' | head -n 3) ;;
  esac
done
mapfile -t files < <(printf '%s\n' "${files[@]}" | sort -u | sed '/^$/d')
if [ ${#files[@]} -eq 0 ]; then
  echo "tidy: no compiled C++ file changed since $base"
  exit 0
fi
echo "tidy: ${#files[@]} files changed since $base: ${files[*]}"
# GCC-only flags in the database that clang does not know are dropped.
printf '%s\n' "${files[@]}" |
  xargs -P "$(nproc)" -n 1 clang-tidy-14 -p "$root/build" --quiet \
    --extra-arg=-Wno-unknown-warning-option --extra-arg=-Wno-ignored-optimization-argument
echo "tidy: no findings"
