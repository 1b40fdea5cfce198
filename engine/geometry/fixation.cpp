// The fixation point of a verging head (symmetric vergence, pan angles,
// closest approach of the optical axes, requested distance) and the
// Vieth-Mueller circle through it, in the cyclopean frame.
#include <cmath>
#include <numbers>
#include <string>

#include <Eigen/Geometry>

#include "geometry/geometry_checks.hpp"
#include "horopter/core/error.hpp"
#include "horopter/vision/geometry.hpp"

namespace horopter {

using geometry_detail::checkBaseline;
using geometry_detail::checkFixation;

namespace {

std::string degrees(double rad) {
  return std::to_string(rad * 180.0 / std::numbers::pi) + " deg";
}

}  // namespace

Eigen::Vector3d fixationFromVergence(double baseline, double vergenceRad) {
  checkBaseline(baseline);
  if (!std::isfinite(vergenceRad) || !(vergenceRad > 0) || !(vergenceRad < std::numbers::pi))
    throw Error(
        "vergence angle must be between 0 and 180 deg (0 = parallel axes, fixation at "
        "infinity), got " +
        degrees(vergenceRad));
  const Eigen::Vector3d f(0, 0, 0.5 * baseline / std::tan(0.5 * vergenceRad));
  checkFixation(f, "the vergence angle " + degrees(vergenceRad));
  return f;
}

Eigen::Vector3d fixationFromPanAngles(double baseline, double leftPanRad, double rightPanRad) {
  checkBaseline(baseline);
  const double limit = 0.5 * std::numbers::pi;
  for (double pan : {leftPanRad, rightPanRad}) {
    if (!std::isfinite(pan) || !(std::abs(pan) < limit))
      throw Error("pan angles must be finite and within +-90 deg of straight ahead, got " +
                  degrees(pan));
  }
  if (!(leftPanRad > rightPanRad))
    throw Error("the optical axes do not cross in front of the head: the left pan (" +
                degrees(leftPanRad) + ") must exceed the right pan (" + degrees(rightPanRad) +
                "); equal pans are parallel axes, a fixation at infinity");
  // Left ray (-B/2 + s sin a, s cos a), right ray (B/2 + t sin b, t cos b):
  // by the sine rule in the triangle (left, right, fixation), the left range is
  // s = B cos b / sin(a - b).
  const double s = baseline * std::cos(rightPanRad) / std::sin(leftPanRad - rightPanRad);
  const Eigen::Vector3d f(-0.5 * baseline + s * std::sin(leftPanRad), 0, s * std::cos(leftPanRad));
  checkFixation(f, "the pan angles " + degrees(leftPanRad) + ", " + degrees(rightPanRad));
  return f;
}

Eigen::Vector3d fixationFromAxes(const Ray& left, const Ray& right) {
  if (!left.origin.allFinite() || !left.direction.allFinite() || !right.origin.allFinite() ||
      !right.direction.allFinite())
    throw Error("optical axes must have finite origins and directions");
  if (!(left.direction.norm() > 0) || !(right.direction.norm() > 0))
    throw Error("optical axes need non-zero directions");
  checkBaseline((right.origin - left.origin).norm());
  const Eigen::Vector3d u = left.direction.normalized();
  const Eigen::Vector3d v = right.direction.normalized();
  const Eigen::Vector3d w = left.origin - right.origin;
  // Minimise |left.origin + s u - right.origin - t v|: the normal equations.
  const double b = u.dot(v), d = u.dot(w), e = v.dot(w);
  const double denom = 1.0 - b * b;
  if (!(denom > 1e-12))
    throw Error("the optical axes are parallel (they meet at infinity): the head does not verge");
  const double s = (b * e - d) / denom;
  const double t = (e - b * d) / denom;
  if (!(s > 0) || !(t > 0))
    throw Error("the optical axes come closest behind the cameras (ranges " + std::to_string(s) +
                ", " + std::to_string(t) + "): the head diverges, there is no fixation in front");
  const Eigen::Vector3d f = 0.5 * (left.origin + s * u + right.origin + t * v);
  checkFixation(f, "the optical axes' closest approach");
  return f;
}

Eigen::Vector3d fixationAtDistance(double baseline, double distance) {
  checkBaseline(baseline);
  if (!std::isfinite(distance) || !(distance > 0))
    throw Error("interaction distance must be a positive, finite length, got " +
                std::to_string(distance));
  return {0, 0, distance};
}

ViethMuellerCircle viethMuellerCircle(double baseline, const Eigen::Vector3d& fixation) {
  checkBaseline(baseline);
  checkFixation(fixation, "the given point");
  // Centre (0, zc) equidistant from (B/2, 0) and (x, z).
  const double h = 0.5 * baseline;
  const double x = fixation.x(), z = fixation.z();
  ViethMuellerCircle c;
  c.centreZ = (x * x + z * z - h * h) / (2.0 * z);
  c.radius = std::hypot(h, c.centreZ);
  c.fixation = {x, z};
  if (!std::isfinite(c.centreZ) || !std::isfinite(c.radius))
    throw Error("the fixation point is too far for a finite circle: bring it nearer");
  return c;
}

bool insideZone(const ViethMuellerCircle& circle, const Eigen::Vector3d& point) {
  return point.z() > 0 && std::hypot(point.x(), point.z() - circle.centreZ) < circle.radius;
}

double vergenceAngleAt(double baseline, const Eigen::Vector3d& point) {
  checkBaseline(baseline);
  const Eigen::Vector3d toLeft = Eigen::Vector3d(-0.5 * baseline, 0, 0) - point;
  const Eigen::Vector3d toRight = Eigen::Vector3d(0.5 * baseline, 0, 0) - point;
  return std::atan2(toLeft.cross(toRight).norm(), toLeft.dot(toRight));
}

}  // namespace horopter
