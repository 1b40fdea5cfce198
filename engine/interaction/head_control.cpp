// Pan/tilt formulas, the limited command and the head-control stage; see
// horopter/interaction/head_control.hpp.
#include "horopter/interaction/head_control.hpp"

#include <algorithm>
#include <cmath>

#include "horopter/core/error.hpp"
#include "horopter/interaction/tracking.hpp"

namespace horopter {

namespace {

struct Point3 {
  double x, y, z;
};

// The head's base frame: world = Ry(pan) Rx(tilt) rig (synthetic_scene.hpp).
Point3 rigToBase(const Point3& p, const hw::HeadAngles& pose) {
  const double ct = std::cos(pose.tilt), st = std::sin(pose.tilt);
  const double cp = std::cos(pose.pan), sp = std::sin(pose.pan);
  const double y1 = ct * p.y + st * p.z, z1 = -st * p.y + ct * p.z;  // Rx(tilt)
  return {cp * p.x + sp * z1, y1, -sp * p.x + cp * z1};              // Ry(pan)
}

// The inverse: rig = Rx(tilt)^T Ry(pan)^T world.
Point3 baseToRig(const Point3& w, const hw::HeadAngles& pose) {
  const double ct = std::cos(pose.tilt), st = std::sin(pose.tilt);
  const double cp = std::cos(pose.pan), sp = std::sin(pose.pan);
  const double x1 = cp * w.x - sp * w.z, z1 = sp * w.x + cp * w.z;  // Ry(pan)^T
  return {x1, ct * w.y - st * z1, st * w.y + ct * z1};              // Rx(tilt)^T
}

}  // namespace

hw::HeadAngles anglesToCentre(const cv::Point3f& p, const hw::HeadAngles& pose) {
  const Point3 w = rigToBase({p.x, p.y, p.z}, pose);
  hw::HeadAngles a = pose;
  a.pan = std::atan2(w.x, w.z);
  a.tilt = std::atan2(w.y, std::hypot(w.x, w.z));
  return a;
}

cv::Point2f pixelAfterHeadTurn(cv::Point2f pixel, double depthM, const hw::HeadAngles& from,
                               const hw::HeadAngles& to, const RectifiedGeometry& rig) {
  if (!(rig.focalPx > 0) || !(depthM > 0) || !std::isfinite(depthM)) return pixel;
  // The left camera sits at (-B/2, 0, 0) in the rig frame.
  const double half = 0.5 * rig.baseline, f = rig.focalPx;
  const Point3 seen{(pixel.x - rig.cx) * depthM / f - half, (pixel.y - rig.cy) * depthM / f,
                    depthM};
  const Point3 now = baseToRig(rigToBase(seen, from), to);
  if (!(now.z > 1e-6)) return pixel;
  return {static_cast<float>(f * (now.x + half) / now.z + rig.cx),
          static_cast<float>(f * now.y / now.z + rig.cy)};
}

double paperAngle(double offsetPx, double focalPx, double distanceM, double lambda) {
  const double phi = distanceM * lambda;
  if (!(focalPx > 0) || !(phi > 0) || !std::isfinite(phi))
    throw Error("the paper's head formula needs a positive focal length, distance and lambda");
  return std::atan(offsetPx / (phi * focalPx));
}

hw::HeadAngles limitCommand(const hw::HeadAngles& pose, const hw::HeadAngles& target,
                            const HeadControlOptions& o) {
  const double step = o.maxRateRadPerS / o.framesPerSecond;
  auto axis = [&](double from, double to, double lo, double hi) {
    const double error = to - from;
    if (std::abs(error) < o.deadbandRad) return std::clamp(from, lo, hi);
    return std::clamp(from + std::clamp(o.gain * error, -step, step), lo, hi);
  };
  hw::HeadAngles c = pose;
  c.pan = axis(pose.pan, target.pan, o.limits.panMin, o.limits.panMax);
  c.tilt = axis(pose.tilt, target.tilt, o.limits.tiltMin, o.limits.tiltMax);
  return c;
}

std::span<const NumberOption<HeadControlOptions>> headControlOptions() {
  using O = HeadControlOptions;
  static const NumberOption<O> table[] = {
      {"maxHandShiftFraction", "--hand-shift", "", 0, 0.5,
       "framing the hands, the most the face moves from its place, as a fraction of the width",
       &O::maxHandShiftFraction},
  };
  return table;
}

void validate(const HeadControlOptions& o) {
  checkRanges(headControlOptions(), o);
  if (!(o.gain > 0 && o.gain <= 1)) throw Error("head control gain must be in (0, 1]");
  if (!(o.maxRateRadPerS > 0) || !(o.framesPerSecond > 0) || o.deadbandRad < 0)
    throw Error("head control rate and frame rate must be positive, the dead band >= 0");
  if (o.actuationDelayFrames < 1) throw Error("the actuation delay must be >= 1 frame");
  if (o.formula == PanTiltFormula::Paper && !(o.lambda > 0))
    throw Error("the paper's head formula needs lambda > 0");
}

bool wantsHeadCommand(const TrackingState& s) {
  return s.election == ElectionState::Godfather && s.head.observed;
}

std::optional<hw::HeadAngles> headCommand(const TrackingState& s, const hw::HeadAngles& pose,
                                          const HeadControlOptions& o) {
  if (!wantsHeadCommand(s)) return std::nullopt;
  hw::HeadAngles target = pose;
  const bool have3d = std::isfinite(s.head.rig.z) && s.head.rig.z > 0;
  if (o.formula == PanTiltFormula::Atan2 && have3d) {
    target = anglesToCentre(s.head.rig, pose);
  } else if (o.focalPx > 0) {
    // The paper's formula (or, without depth, the pinhole angle: phi = 1).
    const bool paper = o.formula == PanTiltFormula::Paper && have3d;
    const double d = paper ? s.head.rig.z : 1.0, lambda = paper ? o.lambda : 1.0;
    target.pan += paperAngle(s.head.image.x - o.cx, o.focalPx, d, lambda);
    target.tilt += paperAngle(s.head.image.y - o.cy, o.focalPx, d, lambda);
  } else {
    return std::nullopt;
  }
  // Frame the hands too: the middle of the head's and hands' extent where
  // the face would be.
  if (o.frameHands && o.focalPx > 0 && o.imageWidth > 0) {
    float lo = s.head.image.x, hi = lo;
    for (const PartState* hand : {&s.leftHand, &s.rightHand})
      if (hand->tracked) {
        lo = std::min(lo, hand->image.x);
        hi = std::max(hi, hand->image.x);
      }
    const double most = o.maxHandShiftFraction * o.imageWidth;
    const double shift = std::clamp(0.5 * (lo + hi) - s.head.image.x, -most, most);
    target.pan += std::atan(shift / o.focalPx);
  }
  // Hold the face above the centre: look down by the angle of that offset.
  if (o.imageHeight > 0 && o.focalPx > 0)
    target.tilt += std::atan((0.5 - o.faceRowFraction) * o.imageHeight / o.focalPx);
  const hw::HeadAngles c = limitCommand(pose, target, o);
  if (c.pan == pose.pan && c.tilt == pose.tilt) return std::nullopt;  // inside the dead band
  return c;
}

}  // namespace horopter
