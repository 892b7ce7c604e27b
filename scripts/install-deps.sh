#!/usr/bin/env bash
# Installs the Debian packages rangefill needs that are missing. Silent when nothing is missing.
# --demo: only what the library and the rangefill binary need (scripts/demo.sh); without it, also
# what the tests, the benchmarks, the Python module and the CI stages need (scripts/test.sh).
set -euo pipefail
packages=(
  build-essential cmake pkg-config
  libeigen3-dev libopencv-dev libopencv-contrib-dev libpcl-dev libceres-dev libsuitesparse-dev
  libcgal-dev nlohmann-json3-dev libcli11-dev zlib1g-dev libpng-dev libjpeg-dev libtiff-dev
  libopenexr-dev
  libjs-three  # report.html's 3D views (three.js, inlined into the binary)
)
if [ "${1:-}" != --demo ]; then
  packages+=(
    libgtest-dev libbenchmark-dev
    pybind11-dev python3-dev python3-numpy python3-pytest  # the Python module (python/)
    python3-matplotlib  # the plots of python/examples/fill_depth_folder.py
    clang-14 clang-tidy-14 libclang-rt-14-dev  # libFuzzer, the sanitizer runtimes, clang-tidy
    chromium  # the browser test of report.html
  )
fi
missing=()
for package in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" ||
    missing+=("$package")
done
[ ${#missing[@]} -eq 0 ] && exit 0
echo "install-deps: installing ${missing[*]}"
sudo=""
[ "$(id -u)" -ne 0 ] && sudo="sudo"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
