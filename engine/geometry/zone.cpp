// Depth and 3-D points from disparity; the figures of the zone of interaction.
#include <algorithm>
#include <cmath>
#include <string>

#include "geometry/geometry_checks.hpp"
#include "horopter/core/error.hpp"
#include "horopter/vision/geometry.hpp"

namespace horopter {

using geometry_detail::checkBaseline;
using geometry_detail::checkRectified;

double depthFromDisparity(const RectifiedGeometry& geometry, double disparityPx) {
  checkRectified(geometry);
  if (!std::isfinite(disparityPx) || !(disparityPx > 0))
    throw Error("disparity must be positive (a point in front of the cameras), got " +
                std::to_string(disparityPx) + " px");
  return geometry.focalPx * geometry.baseline / disparityPx;
}

Eigen::Vector3d pointFromPixel(const RectifiedGeometry& geometry, double u, double v,
                               double disparityPx) {
  if (!std::isfinite(u) || !std::isfinite(v)) throw Error("pixel coordinates must be finite");
  const double z = depthFromDisparity(geometry, disparityPx);
  return {(u - geometry.cx) * z / geometry.focalPx - 0.5 * geometry.baseline,
          (v - geometry.cy) * z / geometry.focalPx, z};
}

FixationPoint toLeftCameraFrame(const RectifiedGeometry& geometry, const Eigen::Vector3d& point) {
  checkBaseline(geometry.baseline);
  return {point.x() + 0.5 * geometry.baseline, point.z()};
}

double zoneWidthAt(const ViethMuellerCircle& circle, double z) {
  const double dz = z - circle.centreZ;
  const double h2 = circle.radius * circle.radius - dz * dz;
  return h2 > 0 ? 2.0 * std::sqrt(h2) : 0.0;
}

ZoneExtent zoneExtent(double baseline, const ViethMuellerCircle& circle) {
  checkBaseline(baseline);
  ZoneExtent e;
  e.radius = circle.radius;
  e.centreZ = circle.centreZ;
  e.farOnAxis = circle.centreZ + circle.radius;
  // A camera's optical axis x = +-B/2 meets the circle at z = 0 and z = 2 zc.
  e.farOnCamera = std::max(0.0, 2.0 * circle.centreZ);
  e.widestZ = std::max(0.0, circle.centreZ);
  e.widest = zoneWidthAt(circle, e.widestZ);
  return e;
}

}  // namespace horopter
