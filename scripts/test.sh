#!/usr/bin/env bash
# Sets everything up and runs every test. Usage: scripts/test.sh [--sanitize]
#   (default)    the Release build's whole ctest suite
#   --sanitize   the unit tests built with ASan+UBSan (the slow real-data
#                accuracy runs, labelled `accuracy`, are left to the default run)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/setup.sh"
"$root/scripts/build.sh" "$@"
jobs="$(nproc 2>/dev/null || echo 2)"
if [ "${1:-}" = "--sanitize" ]; then
  export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1"
  export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
  # PoCL and the ICD loader keep allocations until exit; nothing else is suppressed.
  export LSAN_OPTIONS="suppressions=$root/scripts/lsan.supp:print_suppressions=0"
  cd "$root/build-asan"
  echo "test: ctest (sanitizers, without the accuracy label)"
  ctest --output-on-failure -j "$jobs" -LE accuracy
else
  cd "$root/build"
  echo "test: ctest"
  ctest --output-on-failure -j "$jobs"
fi
