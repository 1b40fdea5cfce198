// Horopter geometry on a rectified pair: the Vieth-Mueller circle through the
// two camera centres and the fixation point, as a per-column disparity
// threshold table for horopterMask.
//
// Frame: left camera centre at the origin, x to the right, z forward; the
// right camera centre at (baseline, 0, 0). Any length unit, used consistently.
#pragma once

#include <cstdint>
#include <vector>

namespace horopter {

struct RectifiedGeometry {
  double focalPx = 0;   // focal length of the rectified pair, pixels
  double cx = 0;        // principal point column, pixels
  double baseline = 0;  // distance between the camera centres (> 0)
};

struct FixationPoint {
  double x = 0;  // lateral position in the left camera frame
  double z = 0;  // depth (> 0)
};

// The fixation point seen at column `u` of the left image with disparity
// `disparityPx` (> 0) pixels.
FixationPoint fixationFromDisparity(const RectifiedGeometry& geometry, double u,
                                    double disparityPx);

// One threshold per column (1/16 px): a pixel of column u is inside the circle
// iff its disparity is >= thresholds[u]. The viewing ray of column u meets the
// circle once more besides the camera centre, at depth
//   Z(u) = (B t + 2 zc) / (t^2 + 1), t = (u - cx) / f,
// where (B/2, zc) is the circle's centre; the threshold is
// ceil(16 f B / Z(u)), clamped to int16. A column whose ray leaves the circle
// behind the camera (Z(u) <= 0) gets INT16_MAX: nothing in it is inside.
// Throws horopter::Error for a non-positive width, focal length, baseline or
// fixation depth.
std::vector<std::int16_t> horopterThresholds(const RectifiedGeometry& geometry, int width,
                                             const FixationPoint& fixation);

}  // namespace horopter
