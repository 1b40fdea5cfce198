#!/usr/bin/env bash
# Device sweep of the tiled matcher's cost-kernel variants
# (HOROPTER_OPENCL_TILED, kernels/opencl/tiled_variant.hpp): from the repo
# root with .gpu carried, `OUT=/some/folder bash scripts/device/sweep_tiled.sh`.
# Runs the two OpenCL `kernels` bench rows (device time) once per variant
# and OpenCV's OpenCL StereoBM rows once, prints a table, and writes under
# $OUT: sweep_tiled.log and sweep_tiled.tar.gz (one bench JSON per run).
# Knobs: VARIANTS (names or key=value lists, space-separated; default
# below), MIN_TIME (0.3 s), T_RUN (limit of one run, 25 s), TOTAL (120 s:
# no run starts past it).
set -u
cd "$(dirname "${BASH_SOURCE[0]}")/../.." || exit 1
. scripts/device/gpu_env.sh  # G (the bundle), OUT (made), the functions
# The named variants and a few key=value ones (block=9: the rows' block
# compiled in), the likeliest first: runs past TOTAL are skipped.
VARIANTS=${VARIANTS:-default rows4-split rows8-split rows=4,split=1,block=9 \
h=4,rows=8,split=1,block=9 block=9 split rows4 p8 g64x4 rowwise planes=8,split=1 \
h=4,rows=8,planes=8,split=1,block=9 w=64,h=4,rows=4,split=1,block=9 rows=2,split=1,block=9}
MIN_TIME=${MIN_TIME:-0.3}
T_RUN=${T_RUN:-25}
TOTAL=${TOTAL:-120}
ROWS='(640x480/d64|1280x720/d128)/w9'

main() {
  local t_start=$SECONDS
  gpu_env_bundle
  gpu_env_icd
  gpu_env_start horopter devices
  cat "$TMP/probe.out"
  local R=${RUN[@]+"${RUN[@]}"}
  mkdir -p "$TMP/sweep"
  : > "$TMP/table"
  # run LABEL FILTER [env assignments...]: one bench process, its rows into the table.
  run() {
    local label=$1 filter=$2
    shift 2
    local file=${label//[^A-Za-z0-9_.-]/_}
    local left=$((t_start + TOTAL - SECONDS)) lim=$T_RUN
    echo
    if [ "$left" -lt 5 ]; then
      echo "===== $label: NOT RUN (TOTAL=$TOTAL s spent)"
      printf '%-36s NOT RUN (budget spent)\n' "$label" >> "$TMP/table"
      return
    fi
    [ "$lim" -gt "$left" ] && lim=$left
    echo "===== [$(date -u +%T)] $label (limit $lim s)"
    local t0=$SECONDS rc
    timeout -k 5 "$lim" env "$@" $R "$G/bin/horopter_bench" --benchmark_filter="$filter" \
      --benchmark_min_time="$MIN_TIME" --benchmark_out="$TMP/sweep/$file.json" \
      --benchmark_out_format=json > "$TMP/run.out" 2>&1
    rc=$?
    cat "$TMP/run.out"
    echo "----- $label: rc=$rc ($((SECONDS - t0)) s)"
    # name, time, and the stage counters (match costs / match decide, ms).
    grep -E '^(disparity|opencv)' "$TMP/run.out" | while read -r name time unit rest; do
      local costs decide
      costs=$(grep -oE 'match costs ms=[0-9.]+[a-z]*' <<< "$rest" | sed 's/.*=//')
      decide=$(grep -oE 'match decide ms=[0-9.]+[a-z]*' <<< "$rest" | sed 's/.*=//')
      printf '%-36s %-34s %9s %-3s costs %-8s decide %-8s\n' "$label" \
        "$(sed -E 's#^(disparity/opencl|opencv_stereobm_ocl)/##; s#/(manual|real)_time$##' <<< "$name")" \
        "$time" "$unit" "${costs:--}" "${decide:--}" >> "$TMP/table"
    done
    [ "$rc" = 0 ] || printf '%-36s rc=%s\n' "$label" "$rc" >> "$TMP/table"
  }
  # OpenCV's rows after the first variant (the default: the baseline), so
  # that a sweep cut short by TOTAL still has both references.
  local first=1
  for v in $VARIANTS; do
    run "$v" "^disparity/opencl/$ROWS/kernels/manual_time\$" \
      HOROPTER_OPENCL_SAD=tiled HOROPTER_OPENCL_TILED="$v"
    [ "$first" = 1 ] && run opencv_stereobm_ocl "^opencv_stereobm_ocl/$ROWS/real_time\$" \
      HOROPTER_OPENCL_SAD=tiled
    first=0
  done
  tar czf "$OUT/sweep_tiled.tar.gz" -C "$TMP" sweep
  echo
  echo "===== table ($((SECONDS - t_start)) s in all; MODE: $MODE; min_time $MIN_TIME s)"
  cat "$TMP/table"
  rm -rf "$TMP"
}

main 2>&1 | tee "$OUT/sweep_tiled.log"
