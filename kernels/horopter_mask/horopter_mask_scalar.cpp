// Scalar reference of horopter masking: THE SPECIFICATION.
//
// Semantics
//   Inputs: disparity D (S16C1, 1/16 px), thresholds T (one int16 per column,
//   1/16 px), invalid marker v; optional image I (U8C1 or U8C3, same size).
//   mask(x, y) = 255 if D(x, y) != v and D(x, y) >= T[x], else 0.
//   A point is inside the Vieth-Mueller circle when it is nearer than the
//   circle along its viewing ray, i.e. its disparity is at least the circle's
//   disparity in that column (the circle itself counts as inside). The
//   geometry (engine/geometry) turns the circle into T once per fixation, on
//   the host, in floating point; this kernel sees integers only. A column
//   where no point in front of the camera is inside holds INT16_MAX.
//   segmented(x, y) = mask(x, y) ? I(x, y) : 0, every channel; written only
//   when a segmented view is given. Only the rows in `rows` are written.
#include <cstdint>

#include "horopter_mask/horopter_mask.hpp"

namespace horopter::scalar {

void horopterMask(const ConstImageView& disparity, std::span<const std::int16_t> thresholds,
                  std::int16_t invalid, const ImageView& mask, const ConstImageView& image,
                  const ImageView& segmented, RowRange rows) {
  const int width = disparity.width;
  const int channels = segmented.empty() ? 0 : static_cast<int>(pixelBytes(image.type));
  for (int y = rows.begin; y < rows.end; ++y) {
    const auto* d = disparity.row<std::int16_t>(y);
    auto* m = mask.row<std::uint8_t>(y);
    for (int x = 0; x < width; ++x) {
      const bool inside = d[x] != invalid && d[x] >= thresholds[x];
      m[x] = inside ? 255 : 0;
    }
    if (channels == 0) continue;
    const auto* in = image.row<std::uint8_t>(y);
    auto* out = segmented.row<std::uint8_t>(y);
    for (int x = 0; x < width; ++x) {
      for (int c = 0; c < channels; ++c) {
        out[x * channels + c] = m[x] ? in[x * channels + c] : 0;
      }
    }
  }
}

}  // namespace horopter::scalar
