// AVX2 lr check: bit-exact with the scalar reference.
//
// Strategy
//   Not vectorised yet: forwards to the scalar reference, which is trivially
//   bit-exact. The vector version replaces this body.
#include "occlusion/occlusion.hpp"

namespace horopter::avx2 {

void leftRightCheck(const ImageView& disparity, const ConstImageView& winnerRight,
                    const StereoParams& params, RowRange rows) {
  scalar::leftRightCheck(disparity, winnerRight, params, rows);
}

}  // namespace horopter::avx2
