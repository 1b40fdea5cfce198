// Laban Movement Analysis features; see include/horopter/movement/lma.hpp.
#include "horopter/movement/lma.hpp"

#include <algorithm>
#include <cmath>

namespace horopter {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;
constexpr int kPathFrames = 15;  // the path whose straightness is Effort Space

// The hands at rest hang beside the body: relative to the sternum, outwards
// and down (metres). A hand far from there, or moving, is the active one.
constexpr double kRestOutM = 0.22, kRestDownM = 0.33;
constexpr double kActiveScore = 0.18;

bool finite(const cv::Point3f& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

// The index of the first edge that `value` is below, so edges {a, b} give
// bins 0 (< a), 1 ([a, b)), 2 (>= b).
template <std::size_t N>
std::uint8_t bin(double value, const double (&edges)[N]) {
  std::uint8_t i = 0;
  while (i < N && value >= edges[i])
    ++i;
  return i;
}

double angleBetween(const cv::Point3d& a, const cv::Point3d& b) {
  const double na = cv::norm(a), nb = cv::norm(b);
  if (na <= 0 || nb <= 0) return 0;
  return std::acos(std::clamp(a.dot(b) / (na * nb), -1.0, 1.0));
}

// The incentre of a triangle: its vertices weighted by the opposite sides.
cv::Point3d incentre(const cv::Point3d& a, const cv::Point3d& b, const cv::Point3d& c,
                     double& perimeter) {
  const double la = cv::norm(b - c), lb = cv::norm(c - a), lc = cv::norm(a - b);
  perimeter = la + lb + lc;
  if (perimeter <= 0) return a;
  return (la * a + lb * b + lc * c) * (1.0 / perimeter);
}

}  // namespace

int angleSector(double angleRad) {
  double deg = std::fmod(angleRad / kDeg + 22.5, 360.0);
  if (deg < 0) deg += 360.0;
  return std::min(7, static_cast<int>(deg / 45.0));
}

int lmaSymbolCardinality(LmaSymbol symbol) {
  switch (symbol) {
    case LmaSymbol::ActiveHand:
      return 3;
    case LmaSymbol::FrontalSector:
    case LmaSymbol::SagittalSector:
    case LmaSymbol::HorizontalSector:
      return 9;
    case LmaSymbol::Speed:
      return 5;
    case LmaSymbol::Curvature:
      return 5;
    case LmaSymbol::Height:
      return 6;
    case LmaSymbol::Lateral:
      return 5;
    case LmaSymbol::Reach:
      return 5;
    case LmaSymbol::IncentreRise:
      return 5;
    case LmaSymbol::Perimeter:
      return 3;
    case LmaSymbol::Body:
      return 8;
    case LmaSymbol::Time:
    case LmaSymbol::Space:
    case LmaSymbol::Flow:
      return 2;
  }
  return 1;
}

const char* lmaSymbolName(LmaSymbol symbol) {
  switch (symbol) {
    case LmaSymbol::ActiveHand:
      return "active-hand";
    case LmaSymbol::FrontalSector:
      return "frontal-sector";
    case LmaSymbol::SagittalSector:
      return "sagittal-sector";
    case LmaSymbol::HorizontalSector:
      return "horizontal-sector";
    case LmaSymbol::Speed:
      return "speed";
    case LmaSymbol::Curvature:
      return "curvature";
    case LmaSymbol::Height:
      return "height";
    case LmaSymbol::Lateral:
      return "lateral";
    case LmaSymbol::Reach:
      return "reach";
    case LmaSymbol::IncentreRise:
      return "incentre-rise";
    case LmaSymbol::Perimeter:
      return "perimeter";
    case LmaSymbol::Body:
      return "body";
    case LmaSymbol::Time:
      return "effort-time";
    case LmaSymbol::Space:
      return "effort-space";
    case LmaSymbol::Flow:
      return "effort-flow";
  }
  return "?";
}

LmaExtractor::LmaExtractor(LmaOptions options) : options_(options) {
  options_.stepFrames = std::max(1, options_.stepFrames);
  options_.smoothFrames = std::max(1, options_.smoothFrames);
}

void LmaExtractor::reset() {
  leftMemory_ = rightMemory_ = {};
  raw_.clear();
  history_.clear();
  haveRest_ = false;
  restFrames_ = 0;
}

bool LmaExtractor::toRig(const PartState& part, double depthHint, cv::Point3d& out) const {
  if (!part.tracked) return false;
  // Depth far from the head's is a stereo miss (the wall behind a hand):
  // take the image position at the hint's depth instead.
  if (finite(part.rig) && part.rig.z > 0 &&
      (depthHint <= 0 || std::abs(part.rig.z - depthHint) < 0.8)) {
    out = {part.rig.x, part.rig.y, part.rig.z};
    return true;
  }
  if (depthHint <= 0 || !std::isfinite(part.image.x) || !std::isfinite(part.image.y)) return false;
  const double z = depthHint;
  out = {(part.image.x - options_.cx) * z / options_.focalPx - 0.5 * options_.baselineM,
         (part.image.y - options_.cy) * z / options_.focalPx, z};
  return true;
}

LmaFeatures LmaExtractor::update(const BodySample& sample) {
  LmaFeatures f;
  Entry e;
  e.timeS = sample.timeS;
  const bool ok = sample.godfather && toRig(sample.head, lastHeadDepth_, e.head);
  if (!ok || (!raw_.empty() && !(sample.timeS > raw_.back().timeS))) {
    reset();
    return f;
  }
  lastHeadDepth_ = e.head.z;
  // A hand without a track, or out of reach of the body (a track on
  // something else), keeps its last offset from the head for a while, then
  // hangs at rest: the other hand's features go on.
  const cv::Point3d sternumNow = e.head + cv::Point3d(0, options_.sternumBelowHeadM, 0);
  auto placeHand = [&](const PartState& part, double side, HandMemory& memory, cv::Point3d& out) {
    if (toRig(part, e.head.z, out) && cv::norm(out - sternumNow) < options_.reachM) {
      memory.offset = out - e.head;
      memory.seenS = sample.timeS;
      memory.valid = true;
      return;
    }
    if (memory.valid && sample.timeS - memory.seenS <= options_.holdHandS) {
      out = e.head + memory.offset;
      return;
    }
    out = sternumNow + cv::Point3d(side * kRestOutM, kRestDownM, 0);
  };
  placeHand(sample.leftHand, 1.0, leftMemory_, e.left);
  placeHand(sample.rightHand, -1.0, rightMemory_, e.right);
  raw_.push_back(e);
  if (static_cast<int>(raw_.size()) > options_.smoothFrames) raw_.pop_front();

  // Smoothed positions; the hands relative to the sternum.
  Smoothed s;
  s.timeS = e.timeS;
  for (const Entry& r : raw_) {
    s.head += r.head;
    s.left += r.left;
    s.right += r.right;
  }
  const double n = static_cast<double>(raw_.size());
  s.head *= 1.0 / n;
  const cv::Point3d sternum = s.head + cv::Point3d(0, options_.sternumBelowHeadM, 0);
  s.left = s.left * (1.0 / n) - sternum;
  s.right = s.right * (1.0 / n) - sternum;
  history_.push_back(s);
  const int k = options_.stepFrames;
  const int keep = std::max(3 * k + 1, kPathFrames + 1);
  if (static_cast<int>(history_.size()) > keep) history_.pop_front();
  const int last = static_cast<int>(history_.size()) - 1;
  if (last < 2 * k) return f;

  auto kinematics = [&](cv::Point3d Smoothed::*part) {
    PartKinematics p;
    const Smoothed& h0 = history_[last];
    const Smoothed& h1 = history_[last - k];
    const Smoothed& h2 = history_[last - 2 * k];
    const cv::Point3d d0 = h0.*part - h1.*part, d1 = h1.*part - h2.*part;
    const double dt0 = h0.timeS - h1.timeS, dt1 = h1.timeS - h2.timeS;
    const cv::Point3d v0 = d0 * (1.0 / dt0), v1 = d1 * (1.0 / dt1);
    const cv::Point3d a0 = (v0 - v1) * (2.0 / (dt0 + dt1));
    p.valid = true;
    p.position = cv::Point3f(h0.*part);
    p.velocity = cv::Point3f(v0);
    p.speed = cv::norm(v0);
    p.acceleration = cv::norm(a0);
    if (last >= 3 * k) {
      const Smoothed& h3 = history_[last - 3 * k];
      const double dt2 = h2.timeS - h3.timeS;
      const cv::Point3d v2 = (h2.*part - h3.*part) * (1.0 / dt2);
      const cv::Point3d a1 = (v1 - v2) * (2.0 / (dt1 + dt2));
      p.jerk = cv::norm(a0 - a1) / dt1;  // a0 is taken about h1, a1 about h2
    }
    p.moving = p.speed >= options_.stillSpeedMps;
    if (p.moving) {
      p.frontalSector = angleSector(std::atan2(-d0.y, d0.x));
      p.sagittalSector = angleSector(std::atan2(-d0.y, -d0.z));
      p.horizontalSector = angleSector(std::atan2(-d0.z, d0.x));
      if (cv::norm(v1) >= options_.stillSpeedMps) p.curvature = angleBetween(d0, d1);
    }
    return p;
  };
  f.head = kinematics(&Smoothed::head);
  f.leftHand = kinematics(&Smoothed::left);
  f.rightHand = kinematics(&Smoothed::right);
  f.valid = true;

  // The active hand: the one farthest from its rest posture (and moving).
  auto activity = [&](const PartKinematics& p, double side) {
    const cv::Point3d rest(side * kRestOutM, kRestDownM, 0);
    return cv::norm(cv::Point3d(p.position) - rest) + 0.1 * p.speed;
  };
  const double left = activity(f.leftHand, 1.0), right = activity(f.rightHand, -1.0);
  f.activeHand = std::max(left, right) < kActiveScore ? 0 : (left >= right ? 1 : 2);
  const PartKinematics& hand =
      (f.activeHand == 1 || (f.activeHand == 0 && left >= right)) ? f.leftHand : f.rightHand;
  const double side = &hand == &f.leftHand ? 1.0 : -1.0;

  // Shape: the head-hands triangle (absolute positions).
  const Smoothed& h0 = history_[last];
  const Smoothed& hk = history_[last - k];
  const cv::Point3d st0 = h0.head + cv::Point3d(0, options_.sternumBelowHeadM, 0);
  const cv::Point3d stk = hk.head + cv::Point3d(0, options_.sternumBelowHeadM, 0);
  double perimeter0 = 0, perimeterK = 0;
  const cv::Point3d in0 = incentre(h0.head, h0.left + st0, h0.right + st0, perimeter0);
  incentre(hk.head, hk.left + stk, hk.right + stk, perimeterK);
  const double incentreY = in0.y - h0.head.y;  // relative to the head, down > 0
  const bool atRest = !f.leftHand.moving && !f.rightHand.moving && f.activeHand == 0;
  restFrames_ = atRest ? restFrames_ + 1 : 0;
  if (!haveRest_ || restFrames_ >= 5) {
    restIncentreY_ = incentreY;
    haveRest_ = true;
  }
  f.incentreRiseM = restIncentreY_ - incentreY;
  const double dt = h0.timeS - hk.timeS;
  f.perimeterRate = perimeter0 > 0 ? (perimeter0 - perimeterK) / (perimeter0 * dt) : 0;
  f.shape = f.perimeterRate > 0.3    ? ShapeFlow::Growing
            : f.perimeterRate < -0.3 ? ShapeFlow::Shrinking
                                     : ShapeFlow::Stable;

  // Body: which parts move (the head in the rig frame: walking, swaying).
  f.movingParts =
      (f.head.moving ? 1u : 0u) | (f.leftHand.moving ? 2u : 0u) | (f.rightHand.moving ? 4u : 0u);

  // Effort of the active hand.
  f.time =
      hand.acceleration > options_.suddenAccelMps2 ? EffortTime::Sudden : EffortTime::Sustained;
  f.flow = hand.jerk > options_.freeJerkMps3 ? EffortFlow::Free : EffortFlow::Bound;
  {
    const auto member = &hand == &f.leftHand ? &Smoothed::left : &Smoothed::right;
    const int first = std::max(0, last - kPathFrames);
    double path = 0;
    for (int i = first + 1; i <= last; ++i)
      path += cv::norm(history_[i].*member - history_[i - 1].*member);
    const double net = cv::norm(history_[last].*member - history_[first].*member);
    f.space = path > 0.03 && net < options_.directStraightness * path ? EffortSpace::Indirect
                                                                      : EffortSpace::Direct;
  }

  // The classifier's symbols.
  auto& sym = f.symbols;
  auto put = [&](LmaSymbol which, int v) {
    sym[static_cast<int>(which)] = static_cast<std::uint8_t>(v);
  };
  put(LmaSymbol::ActiveHand, f.activeHand);
  put(LmaSymbol::FrontalSector, hand.moving ? hand.frontalSector : 8);
  put(LmaSymbol::SagittalSector, hand.moving ? hand.sagittalSector : 8);
  put(LmaSymbol::HorizontalSector, hand.moving ? hand.horizontalSector : 8);
  static constexpr double kSpeedEdges[] = {0.15, 0.4, 0.8, 1.4};
  put(LmaSymbol::Speed, bin(hand.speed, kSpeedEdges));
  static constexpr double kCurvatureEdges[] = {20 * kDeg, 60 * kDeg, 120 * kDeg};
  put(LmaSymbol::Curvature, hand.moving ? 1 + bin(hand.curvature, kCurvatureEdges) : 0);
  const double height = -(hand.position.y + options_.sternumBelowHeadM);  // above the head
  static constexpr double kHeightEdges[] = {-0.45, -0.3, -0.15, 0.0, 0.15};
  put(LmaSymbol::Height, bin(height, kHeightEdges));
  static constexpr double kLateralEdges[] = {0.0, 0.15, 0.3, 0.45};
  put(LmaSymbol::Lateral, bin(side * hand.position.x, kLateralEdges));
  static constexpr double kReachEdges[] = {0.1, 0.2, 0.3, 0.45};
  put(LmaSymbol::Reach, bin(-hand.position.z, kReachEdges));
  static constexpr double kRiseEdges[] = {0.02, 0.06, 0.12, 0.2};
  put(LmaSymbol::IncentreRise, bin(f.incentreRiseM, kRiseEdges));
  put(LmaSymbol::Perimeter, f.shape == ShapeFlow::Shrinking ? 0
                            : f.shape == ShapeFlow::Stable  ? 1
                                                            : 2);
  put(LmaSymbol::Body, static_cast<int>(f.movingParts));
  put(LmaSymbol::Time, f.time == EffortTime::Sudden ? 1 : 0);
  put(LmaSymbol::Space, f.space == EffortSpace::Indirect ? 1 : 0);
  put(LmaSymbol::Flow, f.flow == EffortFlow::Free ? 1 : 0);
  return f;
}

}  // namespace horopter
