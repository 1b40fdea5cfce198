// The OpenCL C sources of the kernels, embedded at build time from the .cl
// files beside each kernel's reference (see embed_cl.cmake).
#pragma once

namespace horopter::opencl::sources {
extern const char* const prefilter;     // kernels/prefilter/prefilter.cl
extern const char* const sad;           // kernels/sad/sad.cl
extern const char* const sadTiled;      // kernels/sad/sad_tiled.cl
extern const char* const sadBand;       // kernels/sad/sad_band.cl
extern const char* const lrCheck;       // kernels/occlusion/lr_check.cl
extern const char* const median;        // kernels/median/median.cl
extern const char* const horopterMask;  // kernels/horopter_mask/horopter_mask.cl
}  // namespace horopter::opencl::sources
