// Per-backend entry points of occlusion cleanup (arguments pre-validated).
#pragma once

#include "horopter/image.hpp"
#include "horopter/stereo_params.hpp"

namespace horopter::scalar {
void leftRightCheck(const ImageView& disparity, const ConstImageView& winnerRight,
                    const StereoParams& params);
void filterSpeckles(const ImageView& disparity, const StereoParams& params);
}  // namespace horopter::scalar
