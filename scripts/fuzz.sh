#!/usr/bin/env bash
# Builds the libFuzzer targets (tests/fuzz/) with clang-14 in build-fuzz/ and
# runs each over its committed corpus (tests/fuzz/corpus/<target>/) for a
# bounded time. Usage: scripts/fuzz.sh [--time SECONDS] [target...]
#   --time S   seconds per target (default $HOROPTER_FUZZ_TIME or 20)
#   targets    default: all six
# New inputs libFuzzer finds go to build-fuzz/corpus/<target>/, never into the
# committed corpus; a crash leaves its input in build-fuzz/crashes/ and fails.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
jobs="$(nproc 2>/dev/null || echo 2)"
seconds="${HOROPTER_FUZZ_TIME:-20}"
if [ "${1:-}" = "--time" ]; then
  seconds="$2"
  shift 2
fi
all=(calibration_file_fuzz movement_model_fuzz body_track_fuzz dynamixel_fuzz ptu_fuzz rmp_fuzz)
if [ "$#" -gt 0 ]; then targets=("$@"); else targets=("${all[@]}"); fi

cxx="${HOROPTER_FUZZ_CXX:-clang++-14}"
command -v "$cxx" >/dev/null || {
  echo "fuzz: $cxx not found (apt-get install clang-14 libclang-rt-14-dev)" >&2
  exit 1
}
dir="$root/build-fuzz"
mkdir -p "$dir"
echo "fuzz: configuring $dir with $cxx"
cmake -S "$root" -B "$dir" -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_C_COMPILER="${cxx/++/}" \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DHOROPTER_FUZZ=ON -DHOROPTER_BUILD_TESTS=OFF \
  -DHOROPTER_BUILD_BENCH=OFF -DHOROPTER_WITH_OPENCL=OFF -DHOROPTER_INSTALL=OFF \
  >"$dir/configure.log" 2>&1 || {
  cat "$dir/configure.log" >&2
  exit 1
}
build_args=()
for t in "${targets[@]}"; do build_args+=(--target "$t"); done
echo "fuzz: building ${targets[*]}"
cmake --build "$dir" -j "$jobs" "${build_args[@]}"

export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
mkdir -p "$dir/crashes"
status=0
for t in "${targets[@]}"; do
  seeds="$root/tests/fuzz/corpus/$t"
  work="$dir/corpus/$t"
  mkdir -p "$work"
  echo "fuzz: $t for ${seconds}s over $seeds"
  if ! (cd "$dir" && TMPDIR="$dir" "$dir/bin/$t" -max_total_time="$seconds" \
        -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
        -artifact_prefix="$dir/crashes/$t-" "$work" "$seeds" >"$dir/$t.log" 2>&1); then
    echo "fuzz: $t FAILED (input in build-fuzz/crashes/, log build-fuzz/$t.log):" >&2
    tail -n 40 "$dir/$t.log" >&2
    status=1
  fi
  grep -aE "^(#[0-9]+[[:space:]]+(INITED|DONE)|Done [0-9]+ runs|stat::number_of_executed_units|stat::peak_rss)" \
    "$dir/$t.log" | sed "s/^/fuzz: $t: /" || true
done
exit "$status"
