// Ground-truth maps and labels; see truth.hpp.
#include "synthetic/truth.hpp"

#include <opencv2/core/utility.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace horopter::synth {

ZoneCircle::ZoneCircle(double baselineM, double vergence) : halfBaseline_(0.5 * baselineM) {
  if (vergence <= 0) {
    fixation_ = centreZ_ = radius_ = std::numeric_limits<double>::infinity();
    return;
  }
  fixation_ = halfBaseline_ / std::tan(0.5 * vergence);
  centreZ_ = (fixation_ * fixation_ - halfBaseline_ * halfBaseline_) / (2 * fixation_);
  radius_ = fixation_ - centreZ_;
}

bool ZoneCircle::inside(double x, double z) const {
  if (!std::isfinite(centreZ_)) return z > 0;
  return x * x + z * z - 2 * z * centreZ_ < halfBaseline_ * halfBaseline_;
}

void allocatePixelTruth(int width, int height, FrameTruth& truth) {
  truth.disparity.create(height, width, CV_16SC1);
  truth.inside.create(height, width, CV_8UC1);
  truth.occluded.create(height, width, CV_8UC1);
}

namespace {

// The truth of pixels x0 <= x < x1 of row y.
void truthSpan(const Camera& left, const Layer& leftLayer, const Layer& rightLayer,
               double baselineM, const ZoneCircle& zone, int y, int x0, int x1, FrameTruth& truth) {
  const int w = left.width;
  const double fb16 = 16.0 * left.f * baselineM;
  const double fb = left.f * baselineM;
  const auto* zl = leftLayer.depth.ptr<double>(y);
  const auto* zr = rightLayer.depth.ptr<double>(y);
  auto* disp = truth.disparity.ptr<std::int16_t>(y);
  auto* in = truth.inside.ptr<std::uint8_t>(y);
  auto* occ = truth.occluded.ptr<std::uint8_t>(y);
  for (int x = x0; x < x1; ++x) {
    const double z = zl[x];
    // round() by hand (halves away from zero; the value is positive):
    // without SSE4.1 std::round is a library call.
    disp[x] = static_cast<std::int16_t>(std::min(32767.0, fb16 / z + 0.5));
    // The pixel's point in the rig frame (the left camera at x = -B/2).
    const double px = -0.5 * baselineM + (x - left.cx) * z / left.f;
    in[x] = zone.inside(px, z) ? 255 : 0;
    // Seen in the right view when the right pixels around x - d look at
    // a surface at (nearly) the same depth.
    const double xr = x - fb / z;
    const int xf = xr >= 0 ? static_cast<int>(xr) : (xr > -1 ? -1 : -2);  // floor, enough here
    bool seen = false;
    for (int xi = xf; xi <= xf + 1; ++xi)
      if (xi >= 0 && xi < w && std::abs(zr[xi] - z) <= 0.02 * z) seen = true;
    occ[x] = seen ? 0 : 255;
  }
}

}  // namespace

void pixelTruth(const Camera& left, const Layer& leftLayer, const Layer& rightLayer,
                double baselineM, const ZoneCircle& zone, cv::Rect rect, FrameTruth& truth,
                double stripes) {
  rect &= cv::Rect(0, 0, left.width, left.height);
  if (rect.empty()) return;
  cv::parallel_for_(
      cv::Range(rect.y, rect.y + rect.height),
      [&](const cv::Range& rows) {
        for (int y = rows.start; y < rows.end; ++y)
          truthSpan(left, leftLayer, rightLayer, baselineM, zone, y, rect.x, rect.x + rect.width,
                    truth);
      },
      stripes);
}

void pixelTruth(const Camera& left, const Layer& leftLayer, const Layer& rightLayer,
                double baselineM, const ZoneCircle& zone, const RowIntervals& intervals,
                FrameTruth& truth, double stripes) {
  cv::parallel_for_(
      cv::Range(0, intervals.height()),
      [&](const cv::Range& rows) {
        for (int y = rows.start; y < rows.end; ++y)
          for (const Interval& in : intervals.row(y))
            truthSpan(left, leftLayer, rightLayer, baselineM, zone, y, std::max(in.x0, 0),
                      std::min(in.x1, left.width), truth);
      },
      stripes);
}

PersonTruth personTruth(const Camera& left, const Layer& leftLayer, double baselineM,
                        const ZoneCircle& zone, int id, const PersonPose& pose) {
  // Rig frame: the left camera's frame shifted by +B/2 along x.
  auto rig = [&](Vec3 world) {
    const Vec3 c = left.toCamera(world);
    return cv::Point3f(static_cast<float>(c.x - 0.5 * baselineM), static_cast<float>(c.y),
                       static_cast<float>(c.z));
  };
  auto pixel = [&](Vec3 world) {
    const Vec3 c = left.toCamera(world);
    return cv::Point2f(static_cast<float>(left.cx + left.f * c.x / c.z),
                       static_cast<float>(left.cy + left.f * c.y / c.z));
  };
  PersonTruth t;
  t.id = id;
  t.movement = pose.movement;
  t.head3d = rig(pose.head);
  t.leftHand3d = rig(pose.hand[0]);
  t.rightHand3d = rig(pose.hand[1]);
  t.head2d = pixel(pose.head);
  t.leftHand2d = pixel(pose.hand[0]);
  t.rightHand2d = pixel(pose.hand[1]);
  t.insideZone = zone.inside(t.head3d.x, t.head3d.z);
  t.faceWidthPx =
      t.head3d.z > 0 ? static_cast<float>(2 * pose.headRadii.x * left.f / t.head3d.z) : 0.0f;
  // Visible: the head centre is in the image and what the pixel sees there
  // is the head (not something in front of it).
  if (!(t.head3d.z > 0) || !(t.head2d.x > -1 && t.head2d.x < left.width) ||
      !(t.head2d.y > -1 && t.head2d.y < left.height))
    return t;
  const int x = std::clamp(static_cast<int>(std::lround(t.head2d.x)), 0, left.width - 1);
  const int y = std::clamp(static_cast<int>(std::lround(t.head2d.y)), 0, left.height - 1);
  t.visible = leftLayer.depth.at<double>(y, x) > t.head3d.z - 2 * pose.headRadii.z;
  return t;
}

}  // namespace horopter::synth
