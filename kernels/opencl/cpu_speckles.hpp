// The OpenCL path's speckle filter, which stays on the CPU (its blob
// labelling joins pixels across the whole frame): both the synchronous
// kernel table and the per-frame pipeline call it.
#pragma once

#include "horopter/kernels/backend.hpp"

namespace horopter::opencl {

// Runs the speckle filter of cpuBackend() (common/cpu_backend.hpp: the CPU
// backend HOROPTER_BACKEND names, else the best available one), so that a
// forced scalar run, or a CPU without AVX2, runs no AVX2 code here either.
// Returns the backend that ran.
const Backend& filterSpecklesOnCpu(const ImageView& disparity, const StereoParams& params);

// Test hook: the backend of the last filterSpecklesOnCpu() call in this
// process, nullptr before the first.
const Backend* lastSpeckleBackend();

}  // namespace horopter::opencl
