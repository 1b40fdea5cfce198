// Per-backend entry points of the x-Sobel prefilter (arguments pre-validated).
#pragma once

#include "horopter/image.hpp"

namespace horopter::scalar {
void prefilterXSobel(const ConstImageView& src, int cap, const ImageView& filtered,
                     const ImageView& texture);
}  // namespace horopter::scalar
