// Zone-limited matching: each frame searches only the disparities where the
// horopter's zone can be, from a little below the frame's smallest
// threshold up to the largest disparity wanted. Pixels inside the zone have
// a disparity at or above their column's threshold, so a matcher that skips
// the disparities below every threshold loses nothing inside the zone when
// the true disparities are found; what can change is that a far pixel whose
// true disparity lies below the range may find a false match inside it
// (`horopter eval-zone` measures that against the full-range mask).
//
// The search is exact for the range it covers: the front end runs the
// reference chain with minDisparity/numDisparities replaced by the range,
// bit for bit on every backend, and writes invalid pixels with the full
// range's marker, so a consumer never sees which range a frame searched.
#pragma once

#include "horopter/core/export.hpp"

#include <cstdint>
#include <span>

#include "horopter/core/image.hpp"
#include "horopter/core/option_table.hpp"
#include "horopter/kernels/backend.hpp"
#include "horopter/kernels/kernels.hpp"
#include "horopter/kernels/stereo_params.hpp"

namespace horopter {

// The disparities one frame searches: minDisparity .. minDisparity +
// numDisparities - 1 px (numDisparities a positive multiple of 16), and the
// guard below them: with guardStep > 0 the matcher also costs every
// guardStep-th disparity below minDisparity, down to the configured range's
// bottom, invalidates a pixel whose winner one of them would have beaten or
// failed the uniqueness test for, and lets them win the right view's pixels
// for the left-right check (kernels.hpp's BelowRangeGuard;
// kernels/sad/sad_scalar.cpp states the rules). A range that starts at the
// configured bottom has nothing below to check.
struct HOROPTER_API SearchRange {
  int minDisparity = 0;
  int numDisparities = 64;
  int guardStep = 0;  // px; 0: no guard
  bool operator==(const SearchRange&) const = default;
};

// The range StereoParams p searches.
HOROPTER_API SearchRange fullRange(const StereoParams& p);
// p with its range replaced.
HOROPTER_API StereoParams withRange(StereoParams p, SearchRange range);
// The matcher's guard for `range` searched within `full` (off when
// range.guardStep is 0).
HOROPTER_API BelowRangeGuard guardBelow(const StereoParams& full, SearchRange range);
// Throws horopter::Error unless `range` is a valid range for `full`'s other
// parameters that starts at or above full.minDisparity (so that its values
// stay above full's invalid marker), with a guardStep within
// 0..kMaxGuardStep.
HOROPTER_API void checkSearchRange(const StereoParams& full, SearchRange range);

// What a front end does to a map it computed over `range`: the pixels that
// hold that range's invalid marker get `full`'s (nothing to do when the
// two ranges start at the same disparity). S16C1 map; `rows` as the kernels'.
HOROPTER_API void restoreInvalidMarker(const ImageView& map, const StereoParams& full,
                                       SearchRange range, RowRange rows = RowRange::all());

struct HOROPTER_API ZoneSearch {
  int enabled = 0;  // 1: each frame's range follows the zone; 0: the full range
  // Disparities searched below the smallest that can reach the frame's
  // smallest threshold, px.
  int marginPx = 4;
  // The largest disparity searched, px; 0: the full range's largest
  // (minDisparity + numDisparities - 1). Above it: nearer the cameras.
  int maxDisparity = 0;
  // The guard below the range (SearchRange::guardStep), px between the
  // disparities it checks; 0: off. 1 (every disparity below the range, each
  // a box-filtered cost without decisions): sparser steps miss the narrow
  // cost minima of fine texture (kernels/README.md, "Zone-limited ranges").
  int guardStep = 1;
};

// Every option of ZoneSearch, declared once (flag, unit, range, help).
HOROPTER_API std::span<const NumberOption<ZoneSearch>> zoneSearchOptions();
// Throws horopter::Error for an option out of range, or a maxDisparity
// below the full range's smallest disparity.
HOROPTER_API void validate(const ZoneSearch& z, const StereoParams& full);

// The largest disparity the pipeline can report, px: the full range's top,
// or the zone search's maxDisparity when it is on and set.
HOROPTER_API int largestDisparity(const StereoParams& full, const ZoneSearch& z);

// The range to search for a frame whose zone has these thresholds (1/16 px,
// one per column, as horopterMask reads them): its top is
// largestDisparity(), its bottom the lowest disparity whose sub-pixel value
// can reach the smallest threshold, less the margin, never below the full
// range's minDisparity; the size is rounded up to a multiple of 16 by
// lowering the bottom (so the top, and with it the band on the left that
// the matcher leaves invalid, stay where they are); its guardStep is the
// zone search's when the range starts above the full range's bottom. With
// zone search off, or no thresholds, the full range.
HOROPTER_API SearchRange zoneSearchRange(const StereoParams& full,
                                         std::span<const std::int16_t> thresholds,
                                         const ZoneSearch& z);

}  // namespace horopter
