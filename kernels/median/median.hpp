// Per-backend entry points of the invalid-aware median (arguments pre-validated).
#pragma once

#include <cstdint>

#include "horopter/image.hpp"

namespace horopter::scalar {
void medianFilter(const ConstImageView& src, const ImageView& dst, int kernelSize, int minValid,
                  std::int16_t invalid);
}  // namespace horopter::scalar
