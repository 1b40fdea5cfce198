// Per-backend entry points of the prefilters: x-Sobel and normalized response
// (arguments pre-validated).
#pragma once

#include "horopter/core/image.hpp"
#include "horopter/kernels/backend.hpp"

namespace horopter {

// The normalized-response prefilter's integer weights, as cv::StereoBM
// computes them (prefilter_normalized_scalar.cpp states their use).
struct NormalizedWeights {
  int centre;  // G = g * s, with g = size * size / 8
  int mean;    // s = (1024 + g) / (2 g)
};
inline NormalizedWeights normalizedWeights(int size) {
  const int g = size * size / 8;
  const int s = (1024 + g) / (2 * g);
  return {g * s, s};
}

}  // namespace horopter

namespace horopter::scalar {
void prefilterXSobel(const ConstImageView& src, int cap, const ImageView& filtered,
                     const ImageView& texture, RowRange rows);
void prefilterNormalized(const ConstImageView& src, int cap, int size, const ImageView& filtered,
                         const ImageView& texture, RowRange rows);
}  // namespace horopter::scalar

// AVX2 version (kernels/prefilter/prefilter_avx2.cpp): bit-exact with scalar; call only
// where the CPU has AVX2 (the registry checks).
namespace horopter::avx2 {
void prefilterXSobel(const ConstImageView& src, int cap, const ImageView& filtered,
                     const ImageView& texture, RowRange rows);
void prefilterNormalized(const ConstImageView& src, int cap, int size, const ImageView& filtered,
                         const ImageView& texture, RowRange rows);
}  // namespace horopter::avx2
