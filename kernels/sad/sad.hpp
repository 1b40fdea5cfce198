// Per-backend entry points of SAD block matching (arguments pre-validated),
// and the geometry every backend shares.
#pragma once

#include <cstddef>
#include <cstdint>

#include "horopter/core/image.hpp"
#include "horopter/kernels/backend.hpp"
#include "horopter/kernels/kernels.hpp"
#include "horopter/kernels/stereo_params.hpp"

namespace horopter {

// MatchRegion and matchRegion: horopter/kernels/kernels.hpp.

// How many disparities the guard checks below params' range (0 when off):
// minDisparity - k * step for k = 1 .. guardCount.
inline int guardCount(const StereoParams& params, const BelowRangeGuard& guard) {
  return guard.step > 0 ? (params.minDisparity - guard.lowest) / guard.step : 0;
}

namespace scalar {
// Which part of the matcher's work matchColumns does (the defaults: all).
struct ColumnWindow {
  int costedEnd = 1 << 30;  // left pixels costed: [bandX0, min(x1, costedEnd))
  int leftEnd = 1 << 30;    // left decisions written: the costed ones below this
  int rightEnd = 1 << 30;   // right winners written: xr in [0, rightEnd), from the costed pixels
};

// matchLeftBand's window (sad_scalar.cpp): the band's left pixels, the right
// winners that have a candidate in the band, and the columns costed for
// them. Shared with the device backends' band kernels.
ColumnWindow leftBandWindow(const MatchRegion& region, const StereoParams& params,
                            const BelowRangeGuard& guard);

// The reference over the window's columns, on rows already filled with the
// invalid marker and "no winner" (matchBlocks fills them, then calls it
// with the whole window).
void matchColumns(const ConstImageView& left, const ConstImageView& right,
                  const ConstImageView& texture, const StereoParams& params,
                  const BelowRangeGuard& guard, const ImageView& disparity,
                  const ImageView& winnerRight, RowRange rows, const ColumnWindow& window);

void matchBlocks(const ConstImageView& left, const ConstImageView& right,
                 const ConstImageView& texture, const StereoParams& params,
                 const BelowRangeGuard& guard, const ImageView& disparity,
                 const ImageView& winnerRight, RowRange rows);

// The left band alone, after a backend's region-only pass over the same rows:
// writes the band's left pixels and every right winner left of x0 - the
// lowest disparity checked (whose candidates include band pixels), from
// costs over the columns left of that end + maxD; nothing without a band. A
// region-only pass followed by this equals matchBlocks.
void matchLeftBand(const ConstImageView& left, const ConstImageView& right,
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

// What avx2::matchBlocks's region pass leaves for the band (no guard):
// least[(y - y0) * stride + xr], y0 the first row of the call's region,
// the least cost over the region's candidates of right pixel xr < x0 -
// minDisparity (65535: none); winnerRight holds their winners.
struct RegionLeast {
  const std::uint16_t* least = nullptr;  // null: not known
  std::ptrdiff_t stride = 0;
};

// scalar::matchLeftBand, bit-exact (kernels/sad/sad_band_avx2.cpp).
// costBound: a bound on every window cost (maxDiff * blockSize^2) where
// the caller knows one, else -1 (derived here); 65535 or more runs the
// scalar reference. With regionLeast (and no guard), only the band's own
// candidates are costed.
void matchLeftBand(const ConstImageView& left, const ConstImageView& right,
                   const ConstImageView& texture, const StereoParams& params,
                   const BelowRangeGuard& guard, const ImageView& disparity,
                   const ImageView& winnerRight, RowRange rows, std::int64_t costBound = -1,
                   const RegionLeast& regionLeast = {});
}  // namespace avx2

}  // namespace horopter
