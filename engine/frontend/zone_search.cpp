#include "horopter/vision/zone_search.hpp"

#include <algorithm>
#include <string>

#include "horopter/core/error.hpp"

namespace horopter {

namespace {

const NumberOption<ZoneSearch> kZoneSearchOptions[] = {
    {"zoneSearch", "--zone-search", "", 0, 1,
     "1: each frame searches only the disparities the zone can have", &ZoneSearch::enabled},
    {"zoneMarginPx", "--zone-margin", "px", 0, 256,
     "disparities searched below the zone's smallest threshold", &ZoneSearch::marginPx},
    {"zoneMaxDisparity", "--zone-max-disparity", "px", 0, 2047,
     "largest disparity searched with --zone-search 1; 0: the full range's",
     &ZoneSearch::maxDisparity},
    {"zoneGuardStep", "--zone-guard-step", "px", 0, 64,
     "with --zone-search 1, also cost every Nth disparity below the range: a pixel whose match "
     "one of them beats (or ties within the uniqueness margin) is dropped, and they take part "
     "in the left-right check; 0: off",
     &ZoneSearch::guardStep},
};

int roundUpTo16(int n) {
  return (n + 15) / 16 * 16;
}

// ceil(a / b) for b > 0.
int ceilDiv(int a, int b) {
  return a >= 0 ? (a + b - 1) / b : -(-a / b);
}

}  // namespace

SearchRange fullRange(const StereoParams& p) {
  return {p.minDisparity, p.numDisparities};
}

StereoParams withRange(StereoParams p, SearchRange range) {
  p.minDisparity = range.minDisparity;
  p.numDisparities = range.numDisparities;
  // A band that asks for more disparities than the range has asks for all.
  p.leftBand = std::min(p.leftBand, range.numDisparities);
  return p;
}

BelowRangeGuard guardBelow(const StereoParams& full, SearchRange range) {
  if (range.guardStep == 0) return {};
  // The kernel checks at most 1024 px below a range.
  return {range.guardStep, std::max(full.minDisparity, range.minDisparity - 1024)};
}

void restoreInvalidMarker(const ImageView& map, const StereoParams& full, SearchRange range,
                          RowRange rows) {
  if (range.minDisparity == full.minDisparity) return;  // the same marker
  const std::int16_t from = invalidDisparity(withRange(full, range));
  const std::int16_t to = invalidDisparity(full);
  const int end = rows.end < 0 ? map.height : rows.end;
  for (int y = rows.begin; y < end; ++y) {
    std::int16_t* row = map.row<std::int16_t>(y);
    std::replace(row, row + map.width, from, to);
  }
}

void checkSearchRange(const StereoParams& full, SearchRange range) {
  if (range.minDisparity < full.minDisparity)
    throw Error("the search range starts at " + std::to_string(range.minDisparity) +
                " px, below the configured minDisparity " + std::to_string(full.minDisparity) +
                " px");
  if (range.guardStep < 0 || range.guardStep > kMaxGuardStep)
    throw Error("the search range's guard step " + std::to_string(range.guardStep) +
                " px is not within 0.." + std::to_string(kMaxGuardStep) + " (0: no guard)");
  validate(withRange(full, range));
}

std::span<const NumberOption<ZoneSearch>> zoneSearchOptions() {
  return kZoneSearchOptions;
}

void validate(const ZoneSearch& z, const StereoParams& full) {
  checkRanges(zoneSearchOptions(), z);
  if (z.maxDisparity != 0 && z.maxDisparity < full.minDisparity)
    throw Error("zoneMaxDisparity (" + std::to_string(z.maxDisparity) +
                " px) lies below the smallest disparity searched (minDisparity " +
                std::to_string(full.minDisparity) + " px)");
  validate(withRange(
      full, {full.minDisparity, roundUpTo16(largestDisparity(full, z) + 1 - full.minDisparity)}));
}

int largestDisparity(const StereoParams& full, const ZoneSearch& z) {
  if (z.enabled && z.maxDisparity > 0) return z.maxDisparity;
  return full.minDisparity + full.numDisparities - 1;
}

SearchRange zoneSearchRange(const StereoParams& full, std::span<const std::int16_t> thresholds,
                            const ZoneSearch& z) {
  if (!z.enabled || thresholds.empty()) return fullRange(full);
  const int top = largestDisparity(full, z) + 1;  // one past the largest
  const int smallest = *std::min_element(thresholds.begin(), thresholds.end());
  // A winner d reports at most 16 d + 8 (the sub-pixel offset is at most
  // half a pixel: kernels/sad/sad_scalar.cpp), so a winner below
  // ceil((t - 8) / 16) never reaches threshold t.
  int bottom = ceilDiv(smallest - kDisparityScale / 2, kDisparityScale) - z.marginPx;
  bottom = std::min(std::max(bottom, full.minDisparity), top - kDisparityScale);
  const int count = roundUpTo16(top - bottom);
  if (top - count > full.minDisparity) return {top - count, count, z.guardStep};
  if (top - count == full.minDisparity) return {top - count, count};
  return {full.minDisparity, roundUpTo16(top - full.minDisparity)};
}

}  // namespace horopter
