// The front-end kernels, validated and dispatched to a backend.
//
// Each function checks its arguments (throwing horopter::Error with a message
// that says what to fix) and then runs the chosen backend. The scalar
// reference in kernels/<kernel>/<kernel>_scalar.cpp states the exact semantics.
// `rows` limits the output rows written (for running stripes of one frame on
// several threads); the default is the whole image. The speckle filter joins
// pixels across the whole image and has no row range.
#pragma once

#include "horopter/core/export.hpp"

#include <cstdint>
#include <span>

#include "horopter/core/image.hpp"
#include "horopter/kernels/backend.hpp"
#include "horopter/kernels/stereo_params.hpp"

namespace horopter {

// Clipped horizontal Sobel. `filtered` (U8C1, may be empty) receives
// clamp(sobel, -cap, cap) + cap in [0, 2 cap]; `texture` (U8C1, may be empty)
// receives |clamp(sobel, -cap, cap)| in [0, cap]. Both sized as `src`.
HOROPTER_API void prefilterXSobel(const ConstImageView& src, int cap, const ImageView& filtered,
                                  const ImageView& texture,
                                  const Backend& backend = scalarBackend(),
                                  RowRange rows = RowRange::all());

// cv::StereoBM's normalized-response prefilter (PREFILTER_NORMALIZED_RESPONSE):
// each pixel's cross-weighted value less its size x size neighbourhood's mean,
// in OpenCV's integer arithmetic, clipped to [-cap, cap]. `filtered` receives
// the clipped value + cap, `texture` its absolute value, as prefilterXSobel's;
// size is odd, 5..255. kernels/prefilter/prefilter_normalized_scalar.cpp
// states the exact arithmetic and borders.
HOROPTER_API void prefilterNormalized(const ConstImageView& src, int cap, int size,
                                      const ImageView& filtered, const ImageView& texture,
                                      const Backend& backend = scalarBackend(),
                                      RowRange rows = RowRange::all());

// The prefilter params.preFilterType names, with its cap and size: writes
// `filtered` (may be empty) and `texture` (may be empty), as the two functions
// above. With PreFilterType::None, `filtered` must be empty and `texture`
// gets the x-Sobel texture (the texture check's input, as in cv::StereoBM's
// chain). Used by both front ends so that they pick the same kernel.
HOROPTER_API void prefilter(const ConstImageView& src, const StereoParams& params,
                            const ImageView& filtered, const ImageView& texture,
                            const Backend& backend = scalarBackend(),
                            RowRange rows = RowRange::all());

// The pixels where every disparity of the range can be evaluated with the
// whole window inside both images: rows [y0, y1), columns [x0, x1). Empty
// (x0 >= x1 or y0 >= y1) when the image is too small for the range. The left
// band (params.leftBand) is the columns [bandX0, x0) of the same rows, each
// matched over the part of the range that fits (kernels/sad/sad_scalar.cpp);
// bandX0 = x0 without it. Every other pixel is invalid.
struct HOROPTER_API MatchRegion {
  int x0 = 0, x1 = 0, y0 = 0, y1 = 0;
  int bandX0 = 0;
  bool empty() const { return x0 >= x1 || y0 >= y1; }
};
HOROPTER_API MatchRegion matchRegion(int width, int height, const StereoParams& params);

// SAD block matching with winner-take-all, texture and uniqueness checks and
// sub-pixel refinement. `left`/`right` are U8C1 (prefiltered or raw), `texture`
// U8C1 (may be empty when params.textureThreshold == 0). Writes `disparity`
// (S16C1, 1/16 px) and `winnerRight` (S16C1, whole px: the right view's own
// winner from the same costs, minDisparity - 1 where it has none).
HOROPTER_API void matchBlocks(const ConstImageView& left, const ConstImageView& right,
                              const ConstImageView& texture, const StereoParams& params,
                              const ImageView& disparity, const ImageView& winnerRight,
                              const Backend& backend = scalarBackend(),
                              RowRange rows = RowRange::all());

// A sparse check of disparities below the searched range, for zone-limited
// matching (horopter/vision/zone_search.hpp): the disparities
// minDisparity - k * step, k = 1, 2, ..., down to `lowest` (the configured
// range's bottom), each costed as the range's are; a pixel whose winner one
// of them would have beaten, or would have failed the winner's uniqueness
// test, is invalid, and a right pixel whose best match one of them is gets
// it as its winner (so that the left-right check sees it).
// kernels/sad/sad_scalar.cpp states the exact rules. step 0 (the default):
// off.
struct HOROPTER_API BelowRangeGuard {
  int step = 0;    // px between checked disparities; 0..kMaxGuardStep
  int lowest = 0;  // the smallest disparity that may be checked, px
};
constexpr int kMaxGuardStep = 1024;

// matchBlocks with the guard below the range: `guard.step` within
// 0..kMaxGuardStep, and when it is on, `guard.lowest` within
// [params.minDisparity - 1024, params.minDisparity]. With step 0, or lowest
// = minDisparity (nothing below to check), the same as matchBlocks.
HOROPTER_API void matchBlocks(const ConstImageView& left, const ConstImageView& right,
                              const ConstImageView& texture, const StereoParams& params,
                              const BelowRangeGuard& guard, const ImageView& disparity,
                              const ImageView& winnerRight,
                              const Backend& backend = scalarBackend(),
                              RowRange rows = RowRange::all());

// Invalidates pixels whose disparity disagrees with the right view's winner by
// more than params.disp12MaxDiff (no-op when it is negative).
HOROPTER_API void leftRightCheck(const ImageView& disparity, const ConstImageView& winnerRight,
                                 const StereoParams& params,
                                 const Backend& backend = scalarBackend(),
                                 RowRange rows = RowRange::all());

// Invalidates connected blobs of at most params.speckleWindowSize pixels
// (no-op when it is 0).
HOROPTER_API void filterSpeckles(const ImageView& disparity, const StereoParams& params,
                                 const Backend& backend = scalarBackend());

// Invalid-aware median that fills holes; `src` and `dst` are S16C1 of the same
// size and must not overlap.
HOROPTER_API void medianFilter(const ConstImageView& src, const ImageView& dst,
                               const MedianParams& median, std::int16_t invalid,
                               const Backend& backend = scalarBackend(),
                               RowRange rows = RowRange::all());

// Horopter mask: 255 where the disparity is valid and >= thresholds[x], else 0.
// `thresholds` holds one entry per column (1/16 px). When `segmented` is not
// empty, it receives `image` (U8C1 or U8C3, the size of `disparity`) with the
// pixels outside the mask zeroed.
HOROPTER_API void horopterMask(const ConstImageView& disparity,
                               std::span<const std::int16_t> thresholds, std::int16_t invalid,
                               const ImageView& mask, const ConstImageView& image = {},
                               const ImageView& segmented = {},
                               const Backend& backend = scalarBackend(),
                               RowRange rows = RowRange::all());

}  // namespace horopter
