#!/usr/bin/env bash
# Installs the Debian packages Horopter needs, only those missing (idempotent).
# Runs apt-get non-interactively; uses sudo when not root.
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  libopencv-dev opencv-data opencv-doc    # OpenCV, its Haar cascades, its sample data
  libavformat-dev                         # run.avi's muxer (engine/cli/mjpeg_avi.hpp)
  python3-skimage                         # scikit-image's data: textures of the synthetic scene
  libeigen3-dev nlohmann-json3-dev        # Eigen; JSON of the evaluation reports
  ocl-icd-opencl-dev opencl-headers pocl-opencl-icd clinfo   # OpenCL, and PoCL on the CPU
  libgtest-dev libgmock-dev libbenchmark-dev
  clang-format
  clang-14 libclang-rt-14-dev             # scripts/fuzz.sh: libFuzzer is in clang-rt's archives
  python3-dev pybind11-dev python3-numpy python3-pytest   # the Python module and its pytest suite
  python3-distributed                     # Dask: evaluation trials spread over a cluster
  python3-venv                            # python3 -m venv, for `pip install .` (README)
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} Debian packages already installed"
  exit 0
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null; then sudo="sudo"; else
    echo "setup: missing packages (${missing[*]}) and not root without sudo: install them as root" >&2
    exit 1
  fi
fi
echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
echo "setup: done"
