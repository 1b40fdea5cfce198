// Scalar reference of the left-right consistency check: THE SPECIFICATION.
//
// Semantics
//   Inputs: disparity D (S16C1, 1/16 px, in place) and winnerRight WR (S16C1,
//   whole px, minDisparity - 1 = none) from matchBlocks. Off when
//   disp12MaxDiff < 0.
//   For every valid left pixel (x, y):
//     dl = (D(x, y) + 8) >> 4        the disparity rounded to whole px, halves up
//     xr = x - dl
//     if 0 <= xr < W and WR(xr, y) != minDisparity - 1
//        and |dl - WR(xr, y)| > disp12MaxDiff:  D(x, y) = invalid
//   A pixel whose right partner is outside the image or has no winner is kept:
//   there is nothing to check it against. Each row is independent; only the
//   rows in `rows` are touched.
#include <cstdint>
#include <cstdlib>

#include "occlusion/occlusion.hpp"

namespace horopter::scalar {

void leftRightCheck(const ImageView& disparity, const ConstImageView& winnerRight,
                    const StereoParams& params, RowRange rows) {
  if (params.disp12MaxDiff < 0) return;
  const std::int16_t invalid = invalidDisparity(params);
  const int noWinner = params.minDisparity - 1;
  const int width = disparity.width;
  for (int y = rows.begin; y < rows.end; ++y) {
    auto* d = disparity.row<std::int16_t>(y);
    const auto* wr = winnerRight.row<std::int16_t>(y);
    for (int x = 0; x < width; ++x) {
      if (d[x] == invalid) continue;
      const int dl = (d[x] + 8) >> 4;
      const int xr = x - dl;
      if (xr < 0 || xr >= width || wr[xr] == noWinner) continue;
      if (std::abs(dl - wr[xr]) > params.disp12MaxDiff) d[x] = invalid;
    }
  }
}

}  // namespace horopter::scalar
