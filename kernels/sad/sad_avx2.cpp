// AVX2 sad: bit-exact with the scalar reference.
//
// Strategy
//   Not vectorised yet: forwards to the scalar reference, which is trivially
//   bit-exact. The vector version replaces this body.
#include "sad/sad.hpp"

namespace horopter::avx2 {

void matchBlocks(const ConstImageView& left, const ConstImageView& right,
                 const ConstImageView& texture, const StereoParams& params,
                 const ImageView& disparity, const ImageView& winnerRight, RowRange rows) {
  scalar::matchBlocks(left, right, texture, params, disparity, winnerRight, rows);
}

}  // namespace horopter::avx2
