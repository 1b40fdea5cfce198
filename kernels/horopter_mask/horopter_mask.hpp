// Per-backend entry points of horopter masking (arguments pre-validated).
#pragma once

#include <cstdint>
#include <span>

#include "horopter/image.hpp"

namespace horopter::scalar {
void horopterMask(const ConstImageView& disparity, std::span<const std::int16_t> thresholds,
                  std::int16_t invalid, const ImageView& mask, const ConstImageView& image,
                  const ImageView& segmented);
}  // namespace horopter::scalar
