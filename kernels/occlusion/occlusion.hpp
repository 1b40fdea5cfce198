// Per-backend entry points of occlusion cleanup (arguments pre-validated).
#pragma once

#include "horopter/core/image.hpp"
#include "horopter/kernels/backend.hpp"
#include "horopter/kernels/stereo_params.hpp"

namespace horopter::scalar {
void leftRightCheck(const ImageView& disparity, const ConstImageView& winnerRight,
                    const StereoParams& params, RowRange rows);
void filterSpeckles(const ImageView& disparity, const StereoParams& params);
}  // namespace horopter::scalar

// AVX2 versions (kernels/occlusion/lr_check_avx2.cpp, speckle_avx2.cpp): bit-exact
// with scalar; call only where the CPU has AVX2 (the registry checks).
namespace horopter::avx2 {
void leftRightCheck(const ImageView& disparity, const ConstImageView& winnerRight,
                    const StereoParams& params, RowRange rows);
void filterSpeckles(const ImageView& disparity, const StereoParams& params);
}  // namespace horopter::avx2
