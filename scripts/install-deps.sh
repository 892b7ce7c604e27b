#!/usr/bin/env bash
# Installs the Debian packages rangefill needs that are missing. Silent when nothing is missing.
# --demo: only what the library and the rangefill binary without the research sub-commands and
# point-cloud meshing need (scripts/demo.sh); without it, also what those, the tests, the
# benchmarks, the Python module and the CI stages need (scripts/test.sh).
set -euo pipefail
packages=(
  build-essential cmake pkg-config
  libeigen3-dev libsuitesparse-dev libcgal-dev nlohmann-json3-dev libcli11-dev zlib1g-dev
  libpng-dev libjpeg-dev libtiff-dev libopenexr-dev
  # The three OpenCV modules the library uses (cmake/OpenCVModules.cmake finds them without
  # libopencv-dev, which installs all of OpenCV, VTK, FFmpeg and GStreamer).
  libopencv-core-dev libopencv-imgproc-dev libopencv-photo-dev
)
if [ "${1:-}" != --demo ]; then
  packages+=(
    libpcl-dev  # point-cloud meshing (RANGEFILL_WITH_PCL)
    libceres-dev libopencv-contrib-dev  # rangefill_eval (RANGEFILL_BUILD_RESEARCH)
    libopencv-dev  # OpenCV's CMake package, with imgcodecs for the tests
    libjs-three  # the 3D views of bench's report.html (three.js, inlined into the binary)
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
