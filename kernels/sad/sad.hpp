// Per-backend entry points of SAD block matching (arguments pre-validated),
// and the geometry every backend shares.
#pragma once

#include "horopter/core/image.hpp"
#include "horopter/kernels/backend.hpp"
#include "horopter/kernels/kernels.hpp"
#include "horopter/kernels/stereo_params.hpp"

namespace horopter {

// The pixels where every disparity of the range can be evaluated with the
// whole window inside both images: rows [y0, y1), columns [x0, x1). Empty
// (x0 >= x1 or y0 >= y1) when the image is too small for the range.
struct MatchRegion {
  int x0 = 0, x1 = 0, y0 = 0, y1 = 0;
  bool empty() const { return x0 >= x1 || y0 >= y1; }
};
MatchRegion matchRegion(int width, int height, const StereoParams& params);

// How many disparities the guard checks below params' range (0 when off):
// minDisparity - k * step for k = 1 .. guardCount.
inline int guardCount(const StereoParams& params, const BelowRangeGuard& guard) {
  return guard.step > 0 ? (params.minDisparity - guard.lowest) / guard.step : 0;
}

namespace scalar {
void matchBlocks(const ConstImageView& left, const ConstImageView& right,
                 const ConstImageView& texture, const StereoParams& params,
                 const BelowRangeGuard& guard, const ImageView& disparity,
                 const ImageView& winnerRight, RowRange rows);
}  // namespace scalar

// AVX2 version (kernels/sad/sad_avx2.cpp): bit-exact with scalar; call only
// where the CPU has AVX2 (the registry checks).
namespace avx2 {
void matchBlocks(const ConstImageView& left, const ConstImageView& right,
                 const ConstImageView& texture, const StereoParams& params,
                 const BelowRangeGuard& guard, const ImageView& disparity,
                 const ImageView& winnerRight, RowRange rows);
}  // namespace avx2

}  // namespace horopter
