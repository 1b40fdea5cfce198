// AVX2 horopter mask: bit-exact with the scalar reference.
//
// Strategy
//   Not vectorised yet: forwards to the scalar reference, which is trivially
//   bit-exact. The vector version replaces this body.
#include "horopter_mask/horopter_mask.hpp"

namespace horopter::avx2 {

void horopterMask(const ConstImageView& disparity, std::span<const std::int16_t> thresholds,
                  std::int16_t invalid, const ImageView& mask, const ConstImageView& image,
                  const ImageView& segmented, RowRange rows) {
  scalar::horopterMask(disparity, thresholds, invalid, mask, image, segmented, rows);
}

}  // namespace horopter::avx2
