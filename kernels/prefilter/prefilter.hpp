// Per-backend entry points of the x-Sobel prefilter (arguments pre-validated).
#pragma once

#include "horopter/core/image.hpp"
#include "horopter/kernels/backend.hpp"

namespace horopter::scalar {
void prefilterXSobel(const ConstImageView& src, int cap, const ImageView& filtered,
                     const ImageView& texture, RowRange rows);
}  // namespace horopter::scalar

// AVX2 version (kernels/prefilter/prefilter_avx2.cpp): bit-exact with scalar; call only
// where the CPU has AVX2 (the registry checks).
namespace horopter::avx2 {
void prefilterXSobel(const ConstImageView& src, int cap, const ImageView& filtered,
                     const ImageView& texture, RowRange rows);
}  // namespace horopter::avx2
