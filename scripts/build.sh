#!/usr/bin/env bash
# Configures and builds incrementally. Usage: scripts/build.sh [--sanitize|--thread] [target...]
#   (default)    Release build in build/
#   --sanitize   AddressSanitizer + UndefinedBehaviorSanitizer build in build-asan/
#   --thread     ThreadSanitizer build in build-tsan/ (RelWithDebInfo, no bench)
# Targets, if given, are built instead of everything.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
jobs="$(nproc 2>/dev/null || echo 2)"

if [ "${1:-}" = "--sanitize" ]; then
  dir="$root/build-asan"
  flags=(-DCMAKE_BUILD_TYPE=RelWithDebInfo -DHOROPTER_SANITIZE=ON -DHOROPTER_BUILD_BENCH=OFF)
elif [ "${1:-}" = "--thread" ]; then
  dir="$root/build-tsan"
  flags=(-DCMAKE_BUILD_TYPE=RelWithDebInfo -DHOROPTER_TSAN=ON -DHOROPTER_BUILD_BENCH=OFF)
elif [ -z "${1:-}" ] || [ "${1#-}" = "${1:-}" ]; then
  dir="$root/build"
  flags=(-DCMAKE_BUILD_TYPE=Release)
else
  echo "usage: scripts/build.sh [--sanitize|--thread] [target...]" >&2
  exit 2
fi

echo "build: configuring $dir"
mkdir -p "$dir"
cmake -S "$root" -B "$dir" "${flags[@]}" >"$dir/configure.log" 2>&1 || {
  cat "$dir/configure.log" >&2
  exit 1
}
case "${1:-}" in --*) shift ;; esac
targets=()
for t in "$@"; do targets+=(--target "$t"); done
echo "build: compiling with $jobs jobs"
cmake --build "$dir" -j "$jobs" "${targets[@]}"
echo "build: binaries in $dir/bin"
