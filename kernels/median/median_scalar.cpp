// Scalar reference of the invalid-aware median that fills holes: THE SPECIFICATION.
//
// Semantics
//   Input: S (S16C1), output O (S16C1, same size, no overlap with S);
//   k = kernelSize (3 or 5), h = k / 2; minValid in 1..k*k; invalid marker v.
//   For each pixel (x, y): V = the values S(x+i, y+j), |i|, |j| <= h, that lie
//   inside the image and are != v (the window is clipped at the borders; no
//   padding values are invented). n = |V|.
//     S(x, y) valid:   O(x, y) = lower median of V (V holds S(x, y), so n >= 1)
//     S(x, y) invalid: O(x, y) = lower median of V if n >= minValid, else v
//   The lower median is the element of rank (n - 1) / 2 (integer division,
//   rank 0 = smallest) of V sorted ascending: an element of V, never an
//   average, so no new disparity values appear.
//   This is how the dense map is interpolated: a hole surrounded mostly by
//   valid disparities takes their median; a hole in a mostly invalid area
//   stays a hole. Only the output rows in `rows` are written; the window reads
//   the input rows around them.
#include <algorithm>
#include <cstdint>

#include "median/median.hpp"

namespace horopter::scalar {

void medianFilter(const ConstImageView& src, const ImageView& dst, int kernelSize, int minValid,
                  std::int16_t invalid, RowRange rows) {
  const int h = kernelSize / 2;
  std::int16_t window[25];
  for (int y = rows.begin; y < rows.end; ++y) {
    auto* out = dst.row<std::int16_t>(y);
    for (int x = 0; x < src.width; ++x) {
      int n = 0;
      for (int j = std::max(0, y - h); j <= std::min(src.height - 1, y + h); ++j) {
        const auto* row = src.row<std::int16_t>(j);
        for (int i = std::max(0, x - h); i <= std::min(src.width - 1, x + h); ++i) {
          if (row[i] != invalid) window[n++] = row[i];
        }
      }
      const bool centreValid = src.row<std::int16_t>(y)[x] != invalid;
      if (!centreValid && n < minValid) {
        out[x] = invalid;
        continue;
      }
      std::sort(window, window + n);
      out[x] = window[(n - 1) / 2];
    }
  }
}

}  // namespace horopter::scalar
