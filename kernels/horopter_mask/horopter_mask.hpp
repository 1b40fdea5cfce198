// Per-backend entry points of horopter masking (arguments pre-validated).
#pragma once

#include <cstdint>
#include <span>

#include "horopter/core/image.hpp"
#include "horopter/kernels/backend.hpp"

namespace horopter::scalar {
void horopterMask(const ConstImageView& disparity, std::span<const std::int16_t> thresholds,
                  std::int16_t invalid, const ImageView& mask, const ConstImageView& image,
                  const ImageView& segmented, RowRange rows);
}  // namespace horopter::scalar

// AVX2 version (kernels/horopter_mask/horopter_mask_avx2.cpp): bit-exact with scalar; call only
// where the CPU has AVX2 (the registry checks).
namespace horopter::avx2 {
void horopterMask(const ConstImageView& disparity, std::span<const std::int16_t> thresholds,
                  std::int16_t invalid, const ImageView& mask, const ConstImageView& image,
                  const ImageView& segmented, RowRange rows);
}  // namespace horopter::avx2
