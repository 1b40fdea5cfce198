// Scalar reference of the speckle filter: THE SPECIFICATION.
//
// Semantics
//   Input: disparity D (S16C1, 1/16 px, in place). Off when
//   speckleWindowSize == 0.
//   Two valid pixels are joined when they are 4-neighbours (left, right, up,
//   down) and their values differ by at most speckleRange (in 1/16 px, as
//   cv::StereoBM). A blob is a connected set of joined pixels; every blob of
//   at most speckleWindowSize pixels is set invalid. Invalid pixels join
//   nothing. The blobs do not depend on the order they are found in, so the
//   result is unique.
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "occlusion/occlusion.hpp"

namespace horopter::scalar {

void filterSpeckles(const ImageView& disparity, const StereoParams& params) {
  if (params.speckleWindowSize == 0) return;
  const std::int16_t invalid = invalidDisparity(params);
  const int width = disparity.width;
  const int height = disparity.height;
  const auto at = [&](int x, int y) -> std::int16_t& { return disparity.row<std::int16_t>(y)[x]; };

  // Flood fill with an explicit stack; `seen` marks pixels already in a blob.
  std::vector<std::uint8_t> seen(static_cast<std::size_t>(width) * height, 0);
  // Pixel indices in 64 bits: a map past 2^31 pixels must not wrap.
  std::vector<std::size_t> stack;
  std::vector<std::size_t> blob;
  for (int y0 = 0; y0 < height; ++y0) {
    for (int x0 = 0; x0 < width; ++x0) {
      const std::size_t start = static_cast<std::size_t>(y0) * width + x0;
      if (seen[start] || at(x0, y0) == invalid) continue;
      seen[start] = 1;
      stack.assign(1, start);
      blob.clear();
      while (!stack.empty()) {
        const std::size_t p = stack.back();
        stack.pop_back();
        blob.push_back(p);
        const int x = static_cast<int>(p % static_cast<std::size_t>(width));
        const int y = static_cast<int>(p / static_cast<std::size_t>(width));
        const int value = at(x, y);
        const int nx[4] = {x - 1, x + 1, x, x};
        const int ny[4] = {y, y, y - 1, y + 1};
        for (int n = 0; n < 4; ++n) {
          if (nx[n] < 0 || nx[n] >= width || ny[n] < 0 || ny[n] >= height) continue;
          const std::size_t q = static_cast<std::size_t>(ny[n]) * width + nx[n];
          const int other = at(nx[n], ny[n]);
          if (seen[q] || other == invalid || std::abs(other - value) > params.speckleRange)
            continue;
          seen[q] = 1;
          stack.push_back(q);
        }
      }
      if (blob.size() <= static_cast<std::size_t>(params.speckleWindowSize)) {
        for (const std::size_t p : blob)
          at(static_cast<int>(p % static_cast<std::size_t>(width)),
             static_cast<int>(p / static_cast<std::size_t>(width))) = invalid;
      }
    }
  }
}

}  // namespace horopter::scalar
