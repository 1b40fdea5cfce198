// The instruction sets of the AVX2 backend, named once. Every function of
// the *_avx2.cpp files carries HOROPTER_AVX2_TARGET (GCC's target attribute)
// instead of per-file -mavx2 flags, so that inline and template code they
// instantiate (std::fill, std::vector, ImageView::row...) stays plain x86-64
// in whatever copy the linker keeps; cpuRunsAvx2Backend() checks every one of
// these features at run time (cpu_info.cpp: keep its list and this one equal,
// a static_assert there compares them). scripts/check_avx_isolation.sh
// guards the result on the built binaries.
#pragma once

#define HOROPTER_AVX2_FEATURES "avx2,bmi,bmi2,popcnt"
#define HOROPTER_AVX2_TARGET __attribute__((target(HOROPTER_AVX2_FEATURES)))

namespace horopter {

// True when this CPU (and its OS, for the ymm state) runs every instruction
// set of HOROPTER_AVX2_FEATURES: the AVX2 backend may run.
bool cpuRunsAvx2Backend();

}  // namespace horopter
