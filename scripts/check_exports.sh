#!/usr/bin/env bash
# libhoropter.so exports its public API and nothing else: every exported
# symbol is the C API (horopter_*) or in namespace horopter (with its type
# information and virtual tables), none is an internal namespace's (detail,
# avx2, scalar, opencl, c_api), and none belongs to a layer the library must not
# hold (the simulator, the evaluations). Prints the count.
# Usage: scripts/check_exports.sh LIBRARY
set -euo pipefail
lib="${1:?usage: check_exports.sh LIBRARY}"
[ -f "$lib" ] || { echo "check_exports: no library at $lib" >&2; exit 1; }
symbols="$(nm -DC --defined-only "$lib" | cut -d' ' -f3-)"
total="$(printf '%s\n' "$symbols" | grep -c .)"
bad=0
outside="$(printf '%s\n' "$symbols" |
  grep -Ev '^(horopter_[a-z0-9_]+$|horopter::|(typeinfo|typeinfo name|vtable|VTT) for horopter::|(non-)?virtual thunk to horopter::)' || true)"
if [ -n "$outside" ]; then
  echo "check_exports: exported outside the horopter API:" >&2
  printf '%s\n' "$outside" | head -20 >&2
  bad=1
fi
internal="$(printf '%s\n' "$symbols" | grep -E 'horopter::(detail|avx2|scalar|opencl|python|cli|c_api)::' || true)"
if [ -n "$internal" ]; then
  echo "check_exports: internal namespaces exported:" >&2
  printf '%s\n' "$internal" | head -20 >&2
  bad=1
fi
upper="$(printf '%s\n' "$symbols" | grep -E 'horopter::(synth|sim)::|SyntheticScene|runTrackingTrial|runInteractionTrial|StereoEval' || true)"
if [ -n "$upper" ]; then
  echo "check_exports: the simulator or the evaluations are in libhoropter:" >&2
  printf '%s\n' "$upper" | head -20 >&2
  bad=1
fi
c_api="$(printf '%s\n' "$symbols" | grep -c '^horopter_' || true)"
if [ "$c_api" -lt 10 ]; then
  echo "check_exports: only $c_api C API functions exported: the export list is broken" >&2
  bad=1
fi
[ "$bad" = 0 ] || exit 1
echo "check_exports: $total symbols exported ($c_api of the C API), all public"
