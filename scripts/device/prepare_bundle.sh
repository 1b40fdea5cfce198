#!/usr/bin/env bash
# Fills .gpu/ from build/bin (run here, after the build): binaries, their
# library closure (with stubs for the codec/GUI libraries), clinfo, the real
# pairs the conformance test reads.
set -euo pipefail
cd "$(dirname "$0")/../.."
G=.gpu
rm -rf $G/bin $G/data $G/root
mkdir -p $G/bin
BINS=(horopter horopter_conformance_tests horopter_opencl_tests horopter_bench)
for b in "${BINS[@]}"; do
  cp build/bin/$b $G/bin/
  strip --strip-unneeded $G/bin/$b 2>/dev/null || true
done
cp /usr/bin/clinfo $G/bin/
python3 scripts/device/make_bundle.py $(printf "$G/bin/%s " "${BINS[@]}") $G/bin/clinfo
src=/work/shared/data
for f in README.md middlebury/tsukuba/im3.png middlebury/tsukuba/im4.png middlebury/teddy/im2.png \
         middlebury/teddy/im6.png middlebury/aloe/aloeL.jpg middlebury/aloe/aloeR.jpg \
         opencv_stereo_calib/left01.jpg opencv_stereo_calib/right01.jpg; do
  mkdir -p "$G/data/$(dirname $f)"
  cp "$src/$f" "$G/data/$f"
done
# What `horopter run` reads at fixed paths of Debian's packages (the scene's
# textures, the face cascade), for run_pipeline.sh: .gpu/root/<path>.
for f in /usr/lib/python3/dist-packages/skimage/data/{astronaut,brick,chelsea,grass,gravel}.png \
         /usr/share/doc/opencv-doc/examples/data/{fruits,messi5,orange}.jpg \
         /usr/share/opencv4/haarcascades/haarcascade_frontalface_default.xml; do
  mkdir -p "$G/root$(dirname "$f")"
  cp "$f" "$G/root$f"
done
# The folder the tests read, fixed at configure time (not greppable in the binary).
sed -n 's/.*-DHOROPTER_SHARED_DATA_DIR=\\"\([^\\]*\)\\".*/\1/p' \
  build/tests/CMakeFiles/horopter_test_support.dir/flags.make | head -n 1 > $G/data_dir.txt
echo "tests read: $(cat $G/data_dir.txt)"
du -sh $G $G/*
