// AVX2 prefilter: bit-exact with the scalar reference.
//
// Strategy
//   Not vectorised yet: forwards to the scalar reference, which is trivially
//   bit-exact. The vector version replaces this body.
#include "prefilter/prefilter.hpp"

namespace horopter::avx2 {

void prefilterXSobel(const ConstImageView& src, int cap, const ImageView& filtered,
                     const ImageView& texture, RowRange rows) {
  scalar::prefilterXSobel(src, cap, filtered, texture, rows);
}

}  // namespace horopter::avx2
