// Scalar reference of the x-Sobel prefilter: THE SPECIFICATION.
//
// Semantics
//   Input: U8C1 image I, W x H. cap in 1..63.
//   sobel(x, y) = (I(x+1, y-1) - I(x-1, y-1))
//               + 2 * (I(x+1, y) - I(x-1, y))
//               + (I(x+1, y+1) - I(x-1, y+1))
//   Rows outside the image reflect without repeating the edge (reflect-101):
//   row -1 reads row 1, row H reads row H-2; a one-row image reads itself.
//   Columns 0 and W-1 have sobel = 0 (no horizontal neighbour on one side), as
//   OpenCV's StereoBM prefilter.
//   c = clamp(sobel, -cap, cap)
//   filtered(x, y) = c + cap   in [0, 2 cap]   (the matching input)
//   texture(x, y)  = |c|       in [0, cap]     (the texture-check input)
//   Either output may be an empty view and is then not written. Only the rows
//   in `rows` are written; the rows above and below are read as neighbours.
#include <algorithm>
#include <cstdint>
#include <cstdlib>

#include "prefilter/prefilter.hpp"

namespace horopter::scalar {

namespace {

int reflect101(int y, int height) {
  if (height == 1) return 0;
  if (y < 0) return -y;
  if (y >= height) return 2 * height - 2 - y;
  return y;
}

}  // namespace

void prefilterXSobel(const ConstImageView& src, int cap, const ImageView& filtered,
                     const ImageView& texture, RowRange rows) {
  const int width = src.width;
  const int height = src.height;
  for (int y = rows.begin; y < rows.end; ++y) {
    const auto* above = src.row<std::uint8_t>(reflect101(y - 1, height));
    const auto* here = src.row<std::uint8_t>(y);
    const auto* below = src.row<std::uint8_t>(reflect101(y + 1, height));
    auto* outFiltered = filtered.empty() ? nullptr : filtered.row<std::uint8_t>(y);
    auto* outTexture = texture.empty() ? nullptr : texture.row<std::uint8_t>(y);
    for (int x = 0; x < width; ++x) {
      int sobel = 0;
      if (x > 0 && x < width - 1) {
        sobel = (above[x + 1] - above[x - 1]) + 2 * (here[x + 1] - here[x - 1]) +
                (below[x + 1] - below[x - 1]);
      }
      const int clipped = std::clamp(sobel, -cap, cap);
      if (outFiltered) outFiltered[x] = static_cast<std::uint8_t>(clipped + cap);
      if (outTexture) outTexture[x] = static_cast<std::uint8_t>(std::abs(clipped));
    }
  }
}

}  // namespace horopter::scalar
