#!/usr/bin/env bash
# Device run of the whole pipeline (`horopter run --no-video` on the built-in synthetic
# scene: detection, tracking, head control, movement classification) with
# the front end on the GPU (`--backend opencl`) and on the CPU (`avx2`),
# pinned to two cores as this project's machines have: from the repo root
# with .gpu carried, `OUT=/some/folder bash scripts/device/run_pipeline.sh`.
# The scene's textures and the face cascade are read at fixed paths of
# Debian's packages; the bundle carries them (.gpu/root, prepare_bundle.sh)
# and they are copied there where missing. Writes each run's summary JSON
# and run_pipeline.log under $OUT. Knobs: CORES (0,1), RUNS (3).
set -u
cd "$(dirname "${BASH_SOURCE[0]}")/../.." || exit 1
. scripts/device/gpu_env.sh  # G (the bundle), OUT (made), the functions
CORES=${CORES:-0,1}
RUNS=${RUNS:-3}
main() {
  gpu_env_bundle
  gpu_env_icd
  gpu_env_start horopter devices
  echo
  echo "===== [$(date -u +%T)] the scene's data files"
  (cd "$G/root" && find . -type f) | while read -r f; do
    [ -f "/$f" ] || { mkdir -p "$(dirname "/$f")" && cp "$G/root/$f" "/$f" && echo "copied /${f#./}"; }
  done
  local summary=()
  # --no-video: the bundle's FFmpeg is a stub (make_bundle.py), so run.avi
  # cannot be written there.
  for i in $(seq 1 "$RUNS"); do
    for backend in avx2 opencl; do
      local name="$backend-$i"
      echo
      echo "===== [$(date -u +%T)] $name: taskset -c $CORES horopter run --backend $backend --no-video --json"
      timeout -k 5 120 taskset -c "$CORES" ${RUN[@]+"${RUN[@]}"} "$G/bin/horopter" run \
        --backend "$backend" --no-video --json -o "$TMP/run-$name" \
        > "$OUT/run_$name.json" 2> "$TMP/run-$name.err"
      local rc=$?
      grep -v '^\[bundle\]' "$TMP/run-$name.err" | tail -n 3
      summary+=("$name rc=$rc $(python3 -c 'import json,sys
d = json.load(open(sys.argv[1])); g = d.get("glass_to_command_ms", {})
print("fps %.1f, glass-to-command median %.1f ms" % (d["fps"], g.get("median", float("nan"))))' \
        "$OUT/run_$name.json" 2>/dev/null || echo "no summary")")
    done
  done
  echo
  echo "===== summary (cores $CORES; MODE: $MODE)"
  printf '%s\n' "${summary[@]}"
  rm -rf "$TMP"
}
main 2>&1 | tee "$OUT/run_pipeline.log"
