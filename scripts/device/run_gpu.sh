#!/usr/bin/env bash
# Device run of the OpenCL backend: `bash scripts/device/run_gpu.sh` from the
# repo root, with .gpu carried (the bundle scripts/device/prepare_bundle.sh
# builds; scripts/device/README.md). Writes under
# $OUT (default /tmp/gpuout): run_gpu.log, conformance.xml, opencl_tests.xml,
# bench.json. Every step prints a header and its exit code; none aborts the rest.
# Limits (seconds) can be changed: T_CONF T_OCL T_BENCH T_BENCH_STRIP, MIN_TIME
# (bench).
set -u
cd "$(dirname "${BASH_SOURCE[0]}")/../.." || exit 1
. scripts/device/gpu_env.sh  # G (the bundle), OUT (made), the functions
T_CONF=${T_CONF:-170}
T_BENCH_STRIP=${T_BENCH_STRIP:-60}
T_OCL=${T_OCL:-60}
T_BENCH=${T_BENCH:-150}
MIN_TIME=${MIN_TIME:-0.3}
TOTAL=${TOTAL:-360}   # no step starts, and none runs, past this many seconds

main() {
  local t_start=$SECONDS
  gpu_env_bundle

  step() {  # step NAME LIMIT_S command args...
    local name=$1 lim=$2
    shift 2
    local left=$((t_start + TOTAL - SECONDS))
    echo
    if [ "$left" -lt 10 ]; then
      echo "===== $name: NOT RUN (the overall budget TOTAL=$TOTAL s is spent)"
      RCS+=("$name: not run (budget spent)")
      return
    fi
    [ "$lim" -gt "$left" ] && lim=$left
    echo "===== [$(date -u +%T)] $name (limit ${lim} s)"
    echo "\$ $*"
    local t0=$SECONDS rc
    timeout -k 5 "$lim" "$@"
    rc=$?
    [ "$rc" = 124 ] && echo "!!!!! $name: TIMED OUT after ${lim} s"
    echo "----- $name: rc=$rc ($((SECONDS - t0)) s)"
    RCS+=("$name: rc=$rc ($((SECONDS - t0)) s)")
  }
  RCS=()

  echo "===== [$(date -u +%T)] machine"
  uname -a
  grep -E '^(PRETTY_NAME)=' /etc/os-release 2>/dev/null
  echo "glibc here: $(ldd --version 2>/dev/null | head -1 || getconf GNU_LIBC_VERSION)"
  echo "cpus: $(nproc); $(grep -m1 'model name' /proc/cpuinfo)"
  grep -m1 -o -w avx2 /proc/cpuinfo >/dev/null && echo "cpu has avx2" || echo "cpu has NO avx2"
  echo "bundle: $(du -sh "$G" | cut -f1) in $G"
  case "$G" in *" "*) echo "WARNING: the bundle path has a space; the carried-glibc mode will break" ;; esac

  if command -v nvidia-smi >/dev/null; then
    step "nvidia-smi" 30 nvidia-smi
  else
    echo "(no nvidia-smi on PATH)"
  fi

  echo
  gpu_env_icd
  if [ -n "$NVLIB" ] && command -v python3 >/dev/null; then
    step "dlopen the ICD library (python3 ctypes, this system's glibc)" 30 python3 -c \
      "import ctypes, sys; ctypes.CDLL(sys.argv[1]); print('dlopen ok:', sys.argv[1])" "$NVLIB"
  fi
  # (listing the cases probes OpenCL: the test list holds one entry per device)
  gpu_env_start horopter_conformance_tests --gtest_list_tests
  echo "conformance test cases listed: $(grep -c '^  ' "$TMP/probe.out")"

  # The real pairs: the tests read the folder fixed at configure time.
  DATA=$(cat "$G/data_dir.txt" 2>/dev/null)
  echo
  echo "===== [$(date -u +%T)] real data (tests read '$DATA')"
  if [ -n "$DATA" ] && [ -f "$DATA/middlebury/tsukuba/im3.png" ]; then
    echo "present already"
  elif [ -n "$DATA" ] && mkdir -p "$(dirname "$DATA")" 2>/dev/null && ln -sfn "$G/data" "$DATA" \
       && [ -f "$DATA/middlebury/tsukuba/im3.png" ]; then
    echo "linked $DATA -> $G/data"
  else
    echo "cannot provide $DATA: the real-pair conformance cases will SKIP"
  fi

  R=${RUN[@]+"${RUN[@]}"}
  echo
  echo "===== [$(date -u +%T)] libraries the loader resolves outside .gpu (glibc only, ideally)"
  for b in horopter horopter_conformance_tests horopter_opencl_tests horopter_bench clinfo; do
    if [ ${#RUN[@]} = 0 ]; then
      LD_TRACE_LOADED_OBJECTS=1 "$G/bin/$b" 2>&1
    else
      "${RUN[@]}" --list "$G/bin/$b" 2>&1
    fi > "$TMP/libs.txt"
    echo "$b: $(grep -c . "$TMP/libs.txt") libraries; outside .gpu:" \
      $(grep -v "$G/" "$TMP/libs.txt" | grep -oE '(=> )?/[^ ]+|not found' | sed 's/=> //' | tr '\n' ' ')
  done
  step "clinfo -l" 30 $R "$G/bin/clinfo" -l
  step "clinfo (first 120 lines)" 30 bash -c '"$@" | head -n 120' _ $R "$G/bin/clinfo"
  step "horopter devices" 30 $R "$G/bin/horopter" devices
  step "horopter devices --json" 30 $R "$G/bin/horopter" devices --json

  step "conformance (HOROPTER_REQUIRE_BACKENDS=scalar,avx2,opencl)" "$T_CONF" \
    env HOROPTER_REQUIRE_BACKENDS=scalar,avx2,opencl $R "$G/bin/horopter_conformance_tests" \
    --gtest_output=xml:"$OUT/conformance.xml"
  step "opencl tests (HOROPTER_REQUIRE_BACKENDS=scalar,avx2,opencl)" "$T_OCL" \
    env HOROPTER_REQUIRE_BACKENDS=scalar,avx2,opencl $R "$G/bin/horopter_opencl_tests" \
    --gtest_output=xml:"$OUT/opencl_tests.xml"

  local S='(640x480/d64/w9|1280x720/d128/w15)'
  local F="^((disparity|frontend)/(opencl[^/]*|avx2)/$S/t[12]|opencv_stereobm/$S/t1"
  F+="|disparity/opencl[^/]*/(640x480/d64|1280x720/d128)/w9/(kernels|transfers|transfers_inflight2)"
  F+="|opencv_stereobm_ocl/(640x480/d64|1280x720/d128)/w9)(/real_time|/manual_time)?\$"
  step "bench rows" 30 $R "$G/bin/horopter_bench" --benchmark_filter="$F" --benchmark_list_tests
  step "bench (min_time $MIN_TIME s)" "$T_BENCH" $R "$G/bin/horopter_bench" \
    --benchmark_filter="$F" --benchmark_min_time="$MIN_TIME" \
    --benchmark_out="$OUT/bench.json" --benchmark_out_format=json
  # The OpenCL rows again with the CPU-shaped match kernel, for the two
  # shapes in one run (`auto` above takes the tiled one on a GPU).
  local FS="^(disparity/opencl[^/]*/(640x480/d64|1280x720/d128)/w9/kernels"
  FS+="|(disparity|frontend)/opencl/$S/t1)(/real_time|/manual_time)?\$"
  step "bench, strip-shaped match (HOROPTER_OPENCL_SAD=strip)" "$T_BENCH_STRIP" \
    env HOROPTER_OPENCL_SAD=strip $R "$G/bin/horopter_bench" \
    --benchmark_filter="$FS" --benchmark_min_time="$MIN_TIME" \
    --benchmark_out="$OUT/bench_strip.json" --benchmark_out_format=json

  echo
  echo "===== summary ($((SECONDS - t_start)) s in all)"
  echo "MODE: $MODE"
  echo "NVIDIA OpenCL library: ${NVLIB:-none}"
  printf '%s\n' "${RCS[@]}"
  for x in conformance opencl_tests; do
    [ -f "$OUT/$x.xml" ] && echo "$x.xml: $(grep -m1 -o '<testsuites [^>]*' "$OUT/$x.xml" \
      | grep -oE '(tests|failures|disabled|errors|time)="[^"]*"' | tr '\n' ' ')" \
      "skipped: $(grep -c '<skipped' "$OUT/$x.xml")"
  done
  rm -rf "$TMP"
}

main 2>&1 | tee "$OUT/run_gpu.log"
