#include "geometry/geometry_checks.hpp"

#include <cmath>

#include "horopter/core/error.hpp"

namespace horopter::geometry_detail {

void checkBaseline(double baseline) {
  if (!std::isfinite(baseline) || !(baseline > 0))
    throw Error("baseline must be a positive, finite distance between the camera centres, got " +
                std::to_string(baseline));
}

void checkRectified(const RectifiedGeometry& g) {
  if (!(g.focalPx > 0) || !std::isfinite(g.focalPx))
    throw Error("focal length must be a positive number of pixels, got " +
                std::to_string(g.focalPx));
  if (!(g.baseline > 0) || !std::isfinite(g.baseline))
    throw Error("baseline must be positive, got " + std::to_string(g.baseline));
  if (!std::isfinite(g.cx)) throw Error("principal point column must be finite");
  if (!std::isfinite(g.cy)) throw Error("principal point row must be finite");
}

void checkFixation(const Eigen::Vector3d& f, const std::string& from) {
  if (!f.allFinite())
    throw Error("fixation from " + from +
                " is not a finite point (at infinity or undefined): verge the cameras more");
  if (!(f.z() > 0))
    throw Error("fixation from " + from + " lies behind or beside the cameras (z = " +
                std::to_string(f.z()) + "): it must be in front, z > 0");
}

}  // namespace horopter::geometry_detail
