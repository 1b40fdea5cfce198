#!/usr/bin/env bash
# Shows that scripts/check_avx_isolation.sh can fail: it must reject a
# program whose plain function was compiled with -mavx2 (and names it), and
# accept the same program when only the horopter::avx2 function carries the
# target attribute, as the kernels do.
# Usage: avx_isolation_selftest.sh CXX WORK_DIR
set -euo pipefail
cxx="$1"
work="$2"
check="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)/scripts/check_avx_isolation.sh"
rm -rf "$work"
mkdir -p "$work/bad/bin" "$work/good/bin"
cat >"$work/program.cpp" <<'CPP'
#include <algorithm>
#include <vector>
#ifdef PER_FUNCTION
#define AVX2 __attribute__((target("avx2,bmi,bmi2,popcnt")))
#else
#define AVX2
#endif
namespace horopter::scalar {
void fillAll(std::vector<int>& v, int x) { std::fill(v.begin(), v.end(), x); }
}  // namespace horopter::scalar
namespace horopter::avx2 {
AVX2 void fillAll(std::vector<int>& v, int x) {
  for (int& e : v) e = e * 3 + x;
}
}  // namespace horopter::avx2
int main(int argc, char**) {
  std::vector<int> v(1000);
  horopter::scalar::fillAll(v, argc);
  horopter::avx2::fillAll(v, argc);
  return v[3] == 4 ? 0 : 1;
}
CPP
"$cxx" -std=c++20 -O3 -mavx2 "$work/program.cpp" -o "$work/bad/bin/program"
"$cxx" -std=c++20 -O3 -DPER_FUNCTION "$work/program.cpp" -o "$work/good/bin/program"

if out="$(bash "$check" "$work/bad" 2>&1)"; then
  echo "FAILED: the check passed a program built with -mavx2 throughout:"
  echo "$out"
  exit 1
fi
echo "$out"
if ! grep -q "horopter::scalar::fillAll" <<<"$out"; then
  echo "FAILED: the check did not name horopter::scalar::fillAll"
  exit 1
fi
out="$(bash "$check" "$work/good" 2>&1)" || {
  echo "FAILED: the check rejected a program whose AVX2 code is only in horopter::avx2:"
  echo "$out"
  exit 1
}
echo "$out"
echo "avx_isolation_selftest: passed"
