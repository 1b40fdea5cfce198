#!/usr/bin/env bash
# Configures and builds incrementally. Usage: scripts/build.sh [--sanitize]
#   (default)    Release build in build/
#   --sanitize   AddressSanitizer + UndefinedBehaviorSanitizer build in build-asan/
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
jobs="$(nproc 2>/dev/null || echo 2)"

if [ "${1:-}" = "--sanitize" ]; then
  dir="$root/build-asan"
  flags=(-DCMAKE_BUILD_TYPE=RelWithDebInfo -DHOROPTER_SANITIZE=ON -DHOROPTER_BUILD_BENCH=OFF)
elif [ -z "${1:-}" ]; then
  dir="$root/build"
  flags=(-DCMAKE_BUILD_TYPE=Release)
else
  echo "usage: scripts/build.sh [--sanitize]" >&2
  exit 2
fi

echo "build: configuring $dir"
mkdir -p "$dir"
cmake -S "$root" -B "$dir" "${flags[@]}" >"$dir/configure.log" 2>&1 || {
  cat "$dir/configure.log" >&2
  exit 1
}
echo "build: compiling with $jobs jobs"
cmake --build "$dir" -j "$jobs"
echo "build: binaries in $dir/bin"
