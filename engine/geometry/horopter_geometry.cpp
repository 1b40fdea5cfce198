#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "horopter/error.hpp"
#include "horopter/geometry.hpp"

namespace horopter {

namespace {

void checkGeometry(const RectifiedGeometry& g) {
  if (!(g.focalPx > 0) || !std::isfinite(g.focalPx))
    throw Error("focal length must be a positive number of pixels, got " +
                std::to_string(g.focalPx));
  if (!(g.baseline > 0) || !std::isfinite(g.baseline))
    throw Error("baseline must be positive, got " + std::to_string(g.baseline));
  if (!std::isfinite(g.cx)) throw Error("principal point column must be finite");
}

}  // namespace

FixationPoint fixationFromDisparity(const RectifiedGeometry& geometry, double u,
                                    double disparityPx) {
  checkGeometry(geometry);
  if (!(disparityPx > 0) || !std::isfinite(disparityPx))
    throw Error("fixation disparity must be positive (a point in front of the cameras), got " +
                std::to_string(disparityPx));
  const double z = geometry.focalPx * geometry.baseline / disparityPx;
  return {z * (u - geometry.cx) / geometry.focalPx, z};
}

std::vector<std::int16_t> horopterThresholds(const RectifiedGeometry& geometry, int width,
                                             const FixationPoint& fixation) {
  checkGeometry(geometry);
  if (width <= 0)
    throw Error("threshold table width must be positive, got " + std::to_string(width));
  if (!(fixation.z > 0) || !std::isfinite(fixation.z) || !std::isfinite(fixation.x))
    throw Error("fixation point must lie in front of the cameras (z > 0), got z = " +
                std::to_string(fixation.z));
  const double b = geometry.baseline;
  const double f = geometry.focalPx;
  // Centre (b/2, zc): equidistant from (0, 0) and from the fixation point.
  const double zc =
      (fixation.x * fixation.x - b * fixation.x + fixation.z * fixation.z) / (2.0 * fixation.z);
  const double int16Max = std::numeric_limits<std::int16_t>::max();
  std::vector<std::int16_t> thresholds(static_cast<std::size_t>(width));
  for (int u = 0; u < width; ++u) {
    const double t = (u - geometry.cx) / f;
    const double zCircle = (b * t + 2.0 * zc) / (t * t + 1.0);
    double threshold = int16Max;
    if (zCircle > 0) threshold = std::min(int16Max, std::ceil(16.0 * f * b / zCircle));
    thresholds[static_cast<std::size_t>(u)] = static_cast<std::int16_t>(threshold);
  }
  return thresholds;
}

}  // namespace horopter
