// AVX2 median: bit-exact with the scalar reference.
//
// Strategy
//   Not vectorised yet: forwards to the scalar reference, which is trivially
//   bit-exact. The vector version replaces this body.
#include "median/median.hpp"

namespace horopter::avx2 {

void medianFilter(const ConstImageView& src, const ImageView& dst, int kernelSize, int minValid,
                  std::int16_t invalid, RowRange rows) {
  scalar::medianFilter(src, dst, kernelSize, minValid, invalid, rows);
}

}  // namespace horopter::avx2
