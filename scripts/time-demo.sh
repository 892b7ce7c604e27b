#!/usr/bin/env bash
# Times ./scripts/demo.sh as a newcomer runs it: in a fresh Debian 12 root (debootstrap, chroot)
# holding only what a new machine has (compilers, cmake, git, GoogleTest, Benchmark, clang tools),
# on a fresh clone of this repository's HEAD. Prints the package installation's and the rest's
# (build and repair) wall times and their sum. Needs root and the network; the base root is made
# once and kept as a tarball in FRESH_DIR (default /var/tmp/rangefill-fresh).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
fresh="${FRESH_DIR:-/var/tmp/rangefill-fresh}"
base_packages=(g++ make cmake git ca-certificates libgtest-dev libgmock-dev libbenchmark-dev
  clang-format clang-tidy cppcheck gdb valgrind python3)
mkdir -p "$fresh"
target="$fresh/root"
cleanup() { umount "$target/proc" "$target/dev" "$target/sys" 2>/dev/null || true; }
trap cleanup EXIT
mount_system() { for d in proc dev sys; do mount --bind "/$d" "$target/$d"; done; }
# Never delete through a bind mount left by a killed run.
remove_target() {
  cleanup
  for d in proc dev sys; do
    ! mountpoint -q "$target/$d" || { echo "time-demo: $target/$d is still mounted" >&2; exit 1; }
  done
  rm -rf "$target"
}

if [ ! -f "$fresh/base.tar" ]; then
  command -v debootstrap >/dev/null || { echo "time-demo: needs debootstrap (apt-get install debootstrap)" >&2; exit 1; }
  echo "time-demo: making the base root (once)"
  remove_target
  debootstrap --variant=minbase bookworm "$target" http://deb.debian.org/debian >/dev/null
  cp /etc/resolv.conf "$target/etc/"
  if [ -f /etc/apt/sources.list.d/debian.sources ]; then  # the host's mirrors and security updates
    rm -f "$target/etc/apt/sources.list"
    cp /etc/apt/sources.list.d/debian.sources "$target/etc/apt/sources.list.d/"
  fi
  mount_system
  chroot "$target" bash -c "apt-get update -qq && DEBIAN_FRONTEND=noninteractive \
    apt-get install -y -qq --no-install-recommends ${base_packages[*]} >/dev/null && apt-get clean"
  cleanup
  tar -C "$target" -cf "$fresh/base.tar" .
fi

remove_target && mkdir -p "$target" && tar -C "$target" -xf "$fresh/base.tar"
mount_system
git clone -q "$root" "$target/root/rangefill"
seconds() { local start=$SECONDS; chroot "$target" bash -c "cd /root/rangefill && $1" >&2; echo $((SECONDS - start)); }
install=$(seconds "./scripts/install-deps.sh --demo")
rest=$(seconds "./scripts/demo.sh")
echo "time-demo: $(git -C "$root" rev-parse --short HEAD): packages ${install} s, build and repair ${rest} s, demo.sh $((install + rest)) s on $(nproc) cores"
