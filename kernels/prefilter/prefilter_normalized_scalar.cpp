// Scalar reference of the normalized-response prefilter: THE SPECIFICATION.
// cv::StereoBM's prefilterNorm (PREFILTER_NORMALIZED_RESPONSE), OpenCV 4.6,
// bit for bit on every image of at least 2 x (size / 2) pixels; on smaller
// ones (where OpenCV reads outside the image) the border rule below holds.
//
// Semantics
//   Input: U8C1 image I, W x H. cap in 1..63, size odd in 5..255, r = size / 2.
//   Borders replicate the edge (not reflect): I(x, y) outside the image reads
//   I(clamp(x, 0, W-1), clamp(y, 0, H-1)), for the window and the neighbours.
//   sum(x, y)  = sum over |dx| <= r, |dy| <= r of I(x+dx, y+dy)   (size^2 pixels)
//   cross(x, y) = 4 I(x, y) + I(x-1, y) + I(x+1, y) + I(x, y-1) + I(x, y+1)
//   OpenCV's integer weights (truncating divisions, as it computes them):
//     g = size * size / 8;  s = (1024 + g) / (2 g);  G = g * s
//   (s is 0 for size >= 91: the response is then 0 everywhere, as OpenCV's.)
//   v = (cross * G - sum * s) >> 10     (arithmetic shift: floor)
//   c = clamp(v, -cap, cap)
//   filtered(x, y) = c + cap   in [0, 2 cap]   (the matching input)
//   texture(x, y)  = |c|       in [0, cap]     (the texture-check input: cv::StereoBM
//                                              sums |filtered - cap| of the left view)
//   Either output may be an empty view and is then not written. Only the rows
//   in `rows` are written; any row of the image may be read.
#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "prefilter/prefilter.hpp"

namespace horopter::scalar {

namespace {

int clampTo(int v, int size) {
  return std::clamp(v, 0, size - 1);
}

}  // namespace

void prefilterNormalized(const ConstImageView& src, int cap, int size, const ImageView& filtered,
                         const ImageView& texture, RowRange rows) {
  const int width = src.width;
  const int height = src.height;
  const int r = size / 2;
  const NormalizedWeights wts = normalizedWeights(size);
  // columnSum[x] = the vertical window's sum at column x, slid down the rows.
  std::vector<int> columnSum(static_cast<std::size_t>(width), 0);
  for (int y = rows.begin; y < rows.end; ++y) {
    if (y == rows.begin) {
      std::fill(columnSum.begin(), columnSum.end(), 0);
      for (int dy = -r; dy <= r; ++dy) {
        const auto* row = src.row<std::uint8_t>(clampTo(y + dy, height));
        for (int x = 0; x < width; ++x)
          columnSum[static_cast<std::size_t>(x)] += row[x];
      }
    } else {
      const auto* entering = src.row<std::uint8_t>(clampTo(y + r, height));
      const auto* leaving = src.row<std::uint8_t>(clampTo(y - r - 1, height));
      for (int x = 0; x < width; ++x)
        columnSum[static_cast<std::size_t>(x)] += entering[x] - leaving[x];
    }
    const auto* above = src.row<std::uint8_t>(clampTo(y - 1, height));
    const auto* here = src.row<std::uint8_t>(y);
    const auto* below = src.row<std::uint8_t>(clampTo(y + 1, height));
    auto* outFiltered = filtered.empty() ? nullptr : filtered.row<std::uint8_t>(y);
    auto* outTexture = texture.empty() ? nullptr : texture.row<std::uint8_t>(y);
    const auto column = [&](int x) {
      return columnSum[static_cast<std::size_t>(clampTo(x, width))];
    };
    int sum = 0;
    for (int dx = -r; dx <= r; ++dx)
      sum += column(dx);
    for (int x = 0; x < width; ++x) {
      if (x > 0) sum += column(x + r) - column(x - r - 1);
      const int cross = 4 * here[x] + here[clampTo(x - 1, width)] + here[clampTo(x + 1, width)] +
                        above[x] + below[x];
      const int v = (cross * wts.centre - sum * wts.mean) >> 10;
      const int clipped = std::clamp(v, -cap, cap);
      if (outFiltered) outFiltered[x] = static_cast<std::uint8_t>(clipped + cap);
      if (outTexture) outTexture[x] = static_cast<std::uint8_t>(std::abs(clipped));
    }
  }
}

}  // namespace horopter::scalar
