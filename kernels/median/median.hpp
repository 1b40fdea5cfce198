// Per-backend entry points of the invalid-aware median (arguments pre-validated).
#pragma once

#include <cstdint>

#include "horopter/core/image.hpp"
#include "horopter/kernels/backend.hpp"

namespace horopter::scalar {
void medianFilter(const ConstImageView& src, const ImageView& dst, int kernelSize, int minValid,
                  std::int16_t invalid, RowRange rows);
}  // namespace horopter::scalar

// AVX2 version (kernels/median/median_avx2.cpp): bit-exact with scalar; call only
// where the CPU has AVX2 (the registry checks).
namespace horopter::avx2 {
void medianFilter(const ConstImageView& src, const ImageView& dst, int kernelSize, int minValid,
                  std::int16_t invalid, RowRange rows);
}  // namespace horopter::avx2
