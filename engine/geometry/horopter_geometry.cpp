// The Vieth-Mueller circle as horopterMask's per-column threshold table; the
// rounding rule is stated in include/horopter/vision/geometry.hpp.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "geometry/geometry_checks.hpp"
#include "horopter/core/error.hpp"
#include "horopter/vision/geometry.hpp"

namespace horopter {

using geometry_detail::checkRectified;

FixationPoint fixationFromDisparity(const RectifiedGeometry& geometry, double u,
                                    double disparityPx) {
  checkRectified(geometry);
  if (!(disparityPx > 0) || !std::isfinite(disparityPx))
    throw Error("fixation disparity must be positive (a point in front of the cameras), got " +
                std::to_string(disparityPx));
  const double z = geometry.focalPx * geometry.baseline / disparityPx;
  return {z * (u - geometry.cx) / geometry.focalPx, z};
}

namespace {

// The table for a circle through both cameras with centre z `zc`.
void fillThresholds(const RectifiedGeometry& geometry, double zc, std::span<std::int16_t> out) {
  const double b = geometry.baseline;
  const double f = geometry.focalPx;
  const double int16Max = std::numeric_limits<std::int16_t>::max();
  const std::size_t width = out.size();
  for (std::size_t u = 0; u < width; ++u) {
    const double t = (static_cast<double>(u) - geometry.cx) / f;
    const double zCircle = (b * t + 2.0 * zc) / (t * t + 1.0);
    double threshold = int16Max;
    if (zCircle > 0) threshold = std::min(int16Max, std::ceil(16.0 * f * b / zCircle));
    out[u] = static_cast<std::int16_t>(threshold);
  }
}

}  // namespace

std::vector<std::int16_t> horopterThresholds(const RectifiedGeometry& geometry, int width,
                                             const FixationPoint& fixation) {
  checkRectified(geometry);
  if (width <= 0)
    throw Error("threshold table width must be positive, got " + std::to_string(width));
  if (!(fixation.z > 0) || !std::isfinite(fixation.z) || !std::isfinite(fixation.x))
    throw Error("fixation point must lie in front of the cameras (z > 0), got z = " +
                std::to_string(fixation.z));
  const double b = geometry.baseline;
  // Centre (b/2, zc) in the left camera frame: equidistant from (0, 0) and
  // from the fixation point.
  const double zc =
      (fixation.x * fixation.x - b * fixation.x + fixation.z * fixation.z) / (2.0 * fixation.z);
  std::vector<std::int16_t> thresholds(static_cast<std::size_t>(width));
  fillThresholds(geometry, zc, thresholds);
  return thresholds;
}

void horopterThresholds(const RectifiedGeometry& geometry, const ViethMuellerCircle& circle,
                        std::span<std::int16_t> out) {
  checkRectified(geometry);
  if (out.empty()) throw Error("threshold table width must be positive, got 0");
  const double h = 0.5 * geometry.baseline;
  const double r = std::hypot(h, circle.centreZ);
  if (!std::isfinite(circle.centreZ) || !(std::abs(circle.radius - r) <= 1e-9 * r))
    throw Error("the circle (centre z " + std::to_string(circle.centreZ) + ", radius " +
                std::to_string(circle.radius) +
                ") does not pass through the camera centres of baseline " +
                std::to_string(geometry.baseline) +
                ": build it with viethMuellerCircle from the same baseline");
  fillThresholds(geometry, circle.centreZ, out);
}

}  // namespace horopter
