#!/usr/bin/env bash
# Fails if any function outside the AVX2 backend holds an instruction that a
# plain x86-64 CPU cannot run: the AVX2 code is compiled for
# HOROPTER_AVX2_FEATURES (kernels/common/cpu_features.hpp) and runs only where
# the CPU probe allows, so any such instruction elsewhere (say, in an inline
# or template function instantiated by an AVX2 file and kept by the linker for
# every caller) would die of an illegal instruction on an older CPU.
#
# Usage: scripts/check_avx_isolation.sh [BUILD_DIR]   (default: build)
# Reads the static and shared libraries under BUILD_DIR and the executables
# of BUILD_DIR/bin (our objects only: system libraries are linked
# dynamically, apart from libgcc's and GoogleTest's start-up and test code).
# Registered as the ctest test hygiene.avx_isolation. QEMU's user mode runs
# AVX2 even when told to emulate an older CPU, so the disassembly is the guard.
#
# Flagged outside the AVX2 code:
#  - ymm/zmm/k registers (AVX, AVX-512);
#  - VEX/EVEX instructions (every v-prefixed mnemonic but VMX's and verr/verw);
#  - BMI1/BMI2 (andn bextr blsi blsmsk blsr bzhi mulx pdep pext rorx sarx shlx
#    shrx), lzcnt and popcnt. Not tzcnt: it is encoded as `rep bsf`, which an
#    older CPU runs as bsf, and GCC emits it for __builtin_ctz in plain x86-64
#    code, where a zero input is undefined anyway (lzcnt would run as bsr,
#    with another result, so GCC never emits it without -mlzcnt).
# AVX2 code: functions whose mangled name lies in namespace horopter::avx2
# (_ZN8horopter4avx2..., its lambdas _ZZN8horopter4avx2...); a template of
# another namespace instantiated with an avx2 type (std::vector<avx2::X>) is
# not AVX2 code, and its mangled name does not start that way.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build}"

if [ "$(uname -m)" != x86_64 ]; then
  echo "check_avx_isolation: skipped: not an x86-64 machine"
  exit 77
fi
if [ ! -d "$build/bin" ]; then
  echo "check_avx_isolation: $build/bin not found: build first" >&2
  exit 1
fi

files=()
while IFS= read -r -d '' f; do files+=("$f"); done < <(
  find "$build" \( -name CMakeFiles -o -name install_consumer \) -prune -o \
    -type f \( -name '*.a' -o -name '*.so' -o -name '*.so.*' \) -print0
  find "$build/bin" -maxdepth 1 -type f -perm -u+x -print0)
if [ "${#files[@]}" -eq 0 ]; then
  echo "check_avx_isolation: no libraries or executables under $build" >&2
  exit 1
fi

report="$(mktemp)"
trap 'rm -f "$report"' EXIT
for f in "${files[@]}"; do
  objdump -d --no-show-raw-insn "$f" | awk -v file="${f#"$build"/}" '
    BEGIN {
      split("andn bextr blsi blsmsk blsr bzhi mulx pdep pext rorx sarx shlx shrx lzcnt popcnt",
            list, " ")
      for (i in list) scalarExt[list[i]] = 1
      split("vmcall vmlaunch vmresume vmxoff vmxon vmread vmwrite vmptrld vmptrst vmclear " \
            "vmfunc vmload vmsave vmrun vmmcall verr verw", list, " ")
      for (i in list) notVex[list[i]] = 1
    }
    /^[0-9a-f]+ <.*>:$/ {
      name = $0
      sub(/^[0-9a-f]+ </, "", name)
      sub(/>:$/, "", name)
      ours = name ~ /^_ZZ?N[rVKRO]*8horopter4avx2/
      print "F", ours
      next
    }
    /^ +[0-9a-f]+:\t/ {
      insn = $0
      sub(/^ +[0-9a-f]+:\t/, "", insn)
      n = split(insn, w, /[ \t]+/)
      m = 1
      while (m < n && w[m] ~ /^(rep|repz|repnz|repe|repne|lock|notrack|bnd|data16|addr32|[c-gs]s|rex(\..*)?|\{vex\}|\{evex\})$/) m++
      op = w[m]
      bad = (insn ~ /%[yz]mm[0-9]|%k[0-7]([^0-9]|$)/) ||
            (op ~ /^v/ && !(op in notVex)) || (op in scalarExt) ||
            (op ~ /^k(mov|and|or|xor|not|shift|test|add|unpck)/)
      if (bad) {
        if (ours) print "A"
        else print "X", file, name, op, insn
      }
    }' >>"$report"
done

# F lines: one per function body; A: an AVX-class instruction in AVX2 code;
# X: one outside it.
read -r bodies avx2Bodies avx2Insns < <(awk '
  $1 == "F" { n++; if ($2 == 1) a++ }
  $1 == "A" { i++ }
  END { print n + 0, a + 0, i + 0 }' "$report")
found="$(grep -c '^X' "$report" || true)"
if [ "$found" -gt 0 ]; then
  echo "check_avx_isolation: FAILED: $found instruction(s) beyond plain x86-64 outside" \
    "horopter::avx2, in these functions (file: function: count: mnemonics, first example):"
  grep '^X' "$report" | awk '{
      key = $2 " " $3
      if (!(key in n)) { order[++k] = key; example[key] = $0; sub(/^X [^ ]+ [^ ]+ [^ ]+ /, "", example[key]) }
      n[key]++
      if (!((key, $4) in seen)) { seen[key, $4] = 1; ops[key] = ops[key] (ops[key] == "" ? "" : ",") $4 }
    }
    END { for (i = 1; i <= k; i++) print order[i], n[order[i]], ops[order[i]], example[order[i]] }' |
    head -100 | while read -r file name count ops example; do
      echo "  $file: $(c++filt "$name"): $count: $ops ($example)"
    done
  exit 1
fi
if [ "$avx2Insns" -eq 0 ]; then
  echo "check_avx_isolation: FAILED: no AVX instruction found even inside horopter::avx2" \
    "($avx2Bodies function bodies): the AVX2 code is missing or this check reads objdump wrong"
  exit 1
fi
echo "check_avx_isolation: passed: ${#files[@]} files, $bodies function bodies checked;" \
  "$avx2Bodies of them in horopter::avx2 (with $avx2Insns AVX/BMI instructions)," \
  "none outside"
