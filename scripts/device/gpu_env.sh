# Sourced by the device scripts (run_gpu.sh, sweep_tiled.sh): the bundle in
# .gpu, the NVIDIA OpenCL library as the only ICD, and how to start the
# binaries. Sourced from the repo root: sets G (the bundle folder) and OUT
# (default /tmp/gpuout, made) at once; its functions set TMP, NVLIB, NVDIR,
# RUN (a prefix for every binary: empty, or the carried glibc's loader) and
# MODE.
G=$PWD/.gpu
OUT=${OUT:-/tmp/gpuout}
mkdir -p "$OUT"

# A scratch folder ($TMP, the OpenCL program cache in it), and the bundle
# runnable: a carry that dropped the exec bits, or a read-only tree, gets a
# copy in $TMP.
gpu_env_bundle() {
  TMP=$(mktemp -d)
  export XDG_CACHE_HOME=$TMP/cache   # the OpenCL program cache
  chmod u+x "$G"/bin/* "$G"/glibc/ld-linux-x86-64.so.2 2>/dev/null
  if [ ! -x "$G/bin/horopter_conformance_tests" ] || [ ! -x "$G/glibc/ld-linux-x86-64.so.2" ]; then
    cp -r "$G" "$TMP/gpu" && chmod u+x "$TMP"/gpu/bin/* "$TMP/gpu/glibc/ld-linux-x86-64.so.2" &&
      G=$TMP/gpu && echo "(exec bits missing: running from a copy in $G)"
  fi
  export HOME=${HOME:-$TMP}
}

# The NVIDIA OpenCL library (OPENCL_ICD_LIB overrides the search, for a dry
# run elsewhere) as the only ICD; without it, the system's ICDs.
gpu_env_icd() {
  echo "===== [$(date -u +%T)] OpenCL ICD"
  ls -la /etc/OpenCL/vendors 2>/dev/null && head -n 3 /etc/OpenCL/vendors/*.icd 2>/dev/null && echo
  NVLIB=${OPENCL_ICD_LIB:-}
  [ -n "$NVLIB" ] || for d in /usr/lib/x86_64-linux-gnu /usr/lib64 /usr/local/nvidia/lib64 /usr/local/nvidia/lib \
           /usr/lib /lib/x86_64-linux-gnu /lib64; do
    for f in "$d"/libnvidia-opencl.so.1 "$d"/libnvidia-opencl.so.*; do
      if [ -e "$f" ]; then NVLIB=$f; break 2; fi
    done
  done
  if [ -z "$NVLIB" ]; then
    echo "not in the usual folders; searching / (at most 60 s)"
    NVLIB=$(timeout 60 find / \( -path /proc -o -path /sys -o -path /dev \) -prune -o \
              -name 'libnvidia-opencl.so*' -print 2>/dev/null | sort | head -n 1)
  fi
  NVDIR=""
  if [ -n "$NVLIB" ]; then
    NVDIR=$(dirname "$NVLIB")
    ls -la "$NVDIR"/libnvidia-opencl* "$NVDIR"/libcuda.so* 2>/dev/null
    mkdir -p "$TMP/vendors"
    echo "$NVLIB" > "$TMP/vendors/nvidia.icd"
    export OCL_ICD_VENDORS=$TMP/vendors
    export OPENCV_OPENCL_DEVICE=${OPENCV_OPENCL_DEVICE:-:GPU:}
    echo "NVIDIA OpenCL: $NVLIB -> OCL_ICD_VENDORS=$OCL_ICD_VENDORS (only this ICD);" \
         "OPENCV_OPENCL_DEVICE=$OPENCV_OPENCL_DEVICE"
  else
    echo "NO libnvidia-opencl found: falling back to the system's ICDs (/etc/OpenCL/vendors);" \
         "the bench's OpenCV-OCL rows use OPENCV_OPENCL_DEVICE=:CPU: (set by the bench)"
  fi
}

# How to start the binaries: this system's glibc (LD_LIBRARY_PATH=.gpu/lib),
# or, if they do not start with it, the carried Debian 12 glibc via its
# loader. `gpu_env_start BINARY ARGS...`: the probe (its output in
# $TMP/probe.out), a command of the bundle's that touches OpenCL.
gpu_env_start() {
  # OpenCV dlopens an ICD loader of its own choosing unless told: ours.
  export OPENCV_OPENCL_RUNTIME=$G/lib/libOpenCL.so.1
  local libpath=$G/lib${NVDIR:+:$NVDIR}
  export LD_LIBRARY_PATH=$libpath${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
  RUN=()
  echo
  echo "===== [$(date -u +%T)] start-up probe"
  local prc=0 bin=$1
  shift
  if [ "${FORCE_CARRIED_GLIBC:-0}" != 1 ]; then
    timeout -k 5 60 "$G/bin/$bin" "$@" > "$TMP/probe.out" 2> "$TMP/probe.err"
    prc=$?
  else
    prc=forced
  fi
  if [ "$prc" = 0 ]; then
    MODE="native: this system's glibc and loader, LD_LIBRARY_PATH=$LD_LIBRARY_PATH"
  elif [ "$prc" = 124 ]; then
    MODE="native (the start-up probe TIMED OUT after 60 s: OpenCL initialisation hangs?)"
  else
    echo "native start failed (rc=$prc; FORCE_CARRIED_GLIBC=${FORCE_CARRIED_GLIBC:-0}):"
    [ -f "$TMP/probe.err" ] && head -n 20 "$TMP/probe.err"
    unset LD_LIBRARY_PATH
    RUN=("$G/glibc/ld-linux-x86-64.so.2" --library-path "$G/lib:$G/glibc${NVDIR:+:$NVDIR}")
    if timeout -k 5 60 "${RUN[@]}" "$G/bin/$bin" "$@" > "$TMP/probe.out" 2> "$TMP/probe.err"; then
      MODE="carried glibc: ${RUN[*]} BINARY"
    else
      echo "carried-glibc start failed too (rc=$?):"
      head -n 20 "$TMP/probe.err"
      MODE="NEITHER WAY STARTS: steps below run natively, to show how they fail"
      RUN=()
      export LD_LIBRARY_PATH=$libpath
    fi
  fi
  echo "MODE: $MODE"
}
