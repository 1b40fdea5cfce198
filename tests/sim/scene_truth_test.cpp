// The synthetic scene's pixel truth: determinism by seed, exact disparity of
// planes (through the public API, in the empty room), zone labels against a
// brute-force circle test, photometric consistency of the pair, head commands
// and bad options.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include <cmath>
#include <cstdint>
#include <limits>

#include "horopter/core/error.hpp"
#include "horopter/sim/synthetic_scene.hpp"
#include "synthetic/room.hpp"

namespace horopter::synth {
namespace {

bool sameMat(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0;
}

TEST(SyntheticScene, SameSeedAndIndexGiveIdenticalFrames) {
  SceneOptions o;
  o.width = 320;
  o.height = 240;
  SyntheticScene a(o), b(o);
  b.render(5);  // a different history must not matter
  for (int index : {0, 45, 90}) {
    const SyntheticFrame fa = a.render(index), fb = b.render(index);
    EXPECT_TRUE(sameMat(fa.left, fb.left)) << index;
    EXPECT_TRUE(sameMat(fa.right, fb.right)) << index;
    EXPECT_TRUE(sameMat(fa.truth.disparity, fb.truth.disparity)) << index;
    EXPECT_TRUE(sameMat(fa.truth.inside, fb.truth.inside)) << index;
    ASSERT_EQ(fa.truth.people.size(), fb.truth.people.size());
    for (std::size_t i = 0; i < fa.truth.people.size(); ++i) {
      EXPECT_EQ(fa.truth.people[i].head3d, fb.truth.people[i].head3d);
      EXPECT_EQ(fa.truth.people[i].movement, fb.truth.people[i].movement);
    }
  }
  o.seed = 2;
  SyntheticScene c(o);
  const SyntheticFrame f1 = a.render(60), f2 = c.render(60);
  EXPECT_FALSE(sameMat(f1.left, f2.left)) << "another seed should move the people";
  EXPECT_NE(f1.truth.people[0].head3d, f2.truth.people[0].head3d);
}

// The analytic rig depth of the plane n . p = c (world) seen by the left
// camera at pixel (x, y), or +inf when the ray does not meet it in front.
double planeDepth(const SyntheticScene& s, double x, double y, cv::Vec3d n, double c) {
  const HeadPose h = s.head();
  // rig -> world: pan about y, then tilt about x (see synthetic_scene.hpp).
  const cv::Matx33d pan(std::cos(h.pan), 0, std::sin(h.pan), 0, 1, 0, -std::sin(h.pan), 0,
                        std::cos(h.pan));
  const cv::Matx33d tilt(1, 0, 0, 0, std::cos(h.tilt), std::sin(h.tilt), 0, -std::sin(h.tilt),
                         std::cos(h.tilt));
  const cv::Matx33d r = pan * tilt;
  const cv::Vec3d centre = r * cv::Vec3d(-0.5 * s.baselineM(), 0, 0);
  const cv::Vec3d d = r * cv::Vec3d((x - s.cx()) / s.focalPx(), (y - s.cy()) / s.focalPx(), 1);
  const double t = (c - n.dot(centre)) / n.dot(d);  // t is the rig depth: d has rig z = 1
  return t > 0 ? t : std::numeric_limits<double>::infinity();
}

// Checks every pixel whose nearest room plane is (n, c) against
// round(16 f B / Z); returns how many pixels it checked.
int checkPlane(const SyntheticScene& s, const FrameTruth& truth, cv::Vec3d n, double c) {
  const cv::Vec3d planes[6][1] = {{{1, 0, 0}}, {{1, 0, 0}}, {{0, 1, 0}},
                                  {{0, 1, 0}}, {{0, 0, 1}}, {{0, 0, 1}}};
  const double offsets[6] = {room::kLeftX,  room::kRightX,  room::kCeilingY,
                             room::kFloorY, room::kBehindZ, room::kBackZ};
  int checked = 0, wrong = 0;
  for (int y = 0; y < truth.disparity.rows; y += 3)
    for (int x = 0; x < truth.disparity.cols; x += 3) {
      // Inside a convex room the visible wall is the nearest plane ahead.
      double nearest = std::numeric_limits<double>::infinity();
      for (int i = 0; i < 6; ++i)
        nearest = std::min(nearest, planeDepth(s, x, y, planes[i][0], offsets[i]));
      const double z = planeDepth(s, x, y, n, c);
      if (z != nearest) continue;
      ++checked;
      const int expected = static_cast<int>(std::lround(16.0 * s.focalPx() * s.baselineM() / z));
      if (truth.disparity.at<std::int16_t>(y, x) != expected && ++wrong <= 5)
        ADD_FAILURE() << "pixel (" << x << ", " << y << "): disparity "
                      << truth.disparity.at<std::int16_t>(y, x) << ", analytic " << expected;
    }
  EXPECT_EQ(wrong, 0);
  return checked;
}

TEST(SyntheticScene, PlaneDisparityEqualsTheAnalyticOne) {
  SceneOptions o;
  o.content = SceneContent::EmptyRoom;
  SyntheticScene s(o);
  s.commandHead({0, 0, 0.06});
  FrameTruth t = s.render(0).truth;
  // The back wall, fronto-parallel at Z = kBackZ: one disparity everywhere.
  const int expected =
      static_cast<int>(std::lround(16 * s.focalPx() * s.baselineM() / room::kBackZ));
  EXPECT_EQ(t.disparity.at<std::int16_t>(static_cast<int>(s.cy()), static_cast<int>(s.cx())),
            expected);
  EXPECT_GT(checkPlane(s, t, {0, 0, 1}, room::kBackZ), 5000);
  // The floor, slanted in the view.
  EXPECT_GT(checkPlane(s, t, {0, 1, 0}, room::kFloorY), 1000);
  // With the head turned, the walls are slanted in the rig frame.
  s.commandHead({0.3, 0.2, 0.06});
  t = s.render(0).truth;
  EXPECT_GT(checkPlane(s, t, {0, 0, 1}, room::kBackZ), 1000);
  EXPECT_GT(checkPlane(s, t, {0, 1, 0}, room::kFloorY), 1000);
  EXPECT_GT(checkPlane(s, t, {1, 0, 0}, room::kRightX), 1000);
}

TEST(SyntheticScene, InsideLabelsAgreeWithABruteForceCircleTest) {
  SyntheticScene s(SceneOptions{});
  for (double vergence : {0.06, 0.1, 0.0}) {
    s.commandHead({0.05, 0, vergence});
    const FrameTruth t = s.render(70).truth;
    const double b = s.baselineM(), f = s.focalPx();
    // The circle through (-B/2, 0), (B/2, 0) and the fixation point (0, D).
    const double d = vergence > 0 ? 0.5 * b / std::tan(0.5 * vergence) : 0;
    if (vergence > 0)
      EXPECT_NEAR(t.fixationDistanceM, d, 1e-9);
    else
      EXPECT_EQ(t.fixationDistanceM, std::numeric_limits<double>::infinity());
    const double zc = vergence > 0 ? (d * d - 0.25 * b * b) / (2 * d) : 0;
    const double r = vergence > 0 ? d - zc : 0;
    int insideCount = 0, mismatches = 0;
    for (int y = 0; y < t.disparity.rows; y += 2)
      for (int x = 0; x < t.disparity.cols; x += 2) {
        const double disp = t.disparity.at<std::int16_t>(y, x) / 16.0;
        const double z = f * b / disp;
        const double px = (x - s.cx()) * z / f - 0.5 * b;
        const bool in = vergence > 0 ? std::hypot(px, z - zc) < r : true;
        // The label comes from the exact depth, the check from the rounded
        // disparity: skip points within the rounding of the circle.
        const double margin = vergence > 0 ? std::abs(std::hypot(px, z - zc) - r) : 1;
        if (margin < 0.01 * z) continue;
        insideCount += in;
        mismatches += in != (t.inside.at<std::uint8_t>(y, x) == 255);
      }
    EXPECT_EQ(mismatches, 0) << "vergence " << vergence;
    EXPECT_GT(insideCount, 500) << "the main person should be inside, vergence " << vergence;
  }
}

TEST(SyntheticScene, LeftAndRightAgreeAlongTheTrueDisparity) {
  SyntheticScene s(SceneOptions{});
  for (int index : {0, 75}) {
    const SyntheticFrame f = s.render(index);
    cv::Mat l, r;
    f.left.convertTo(l, CV_32FC3);
    f.right.convertTo(r, CV_32FC3);
    double sum = 0;
    int count = 0, bad = 0;
    for (int y = 2; y < l.rows - 2; y += 2)
      for (int x = 2; x < l.cols - 2; x += 2) {
        if (f.truth.occluded.at<std::uint8_t>(y, x)) continue;
        const double xr = x - f.truth.disparity.at<std::int16_t>(y, x) / 16.0;
        const int x0 = static_cast<int>(std::floor(xr));
        if (x0 < 0 || x0 + 1 >= r.cols) continue;
        // Skip depth edges: there a pixel mixes nothing, but its neighbours
        // in the other view may belong to another surface.
        const cv::Mat dRow = f.truth.disparity.row(y);
        const int dc = dRow.at<std::int16_t>(x);
        if (std::abs(dRow.at<std::int16_t>(x - 2) - dc) > 16 ||
            std::abs(dRow.at<std::int16_t>(x + 2) - dc) > 16)
          continue;
        const float a = static_cast<float>(xr - x0);
        const cv::Vec3f rv = r.at<cv::Vec3f>(y, x0) * (1 - a) + r.at<cv::Vec3f>(y, x0 + 1) * a;
        const double diff = cv::norm(l.at<cv::Vec3f>(y, x) - rv, cv::NORM_L1) / 3;
        sum += diff;
        ++count;
        bad += diff > 40;
      }
    ASSERT_GT(count, 10000);
    EXPECT_LT(sum / count, 4.0) << "mean absolute difference per channel, frame " << index;
    EXPECT_LT(bad, count / 100) << "frame " << index;
  }
}

TEST(SyntheticScene, CommandHeadTurnsTheView) {
  SyntheticScene s(SceneOptions{});
  const SyntheticFrame a = s.render(100);
  s.commandHead({0.2, -0.05, 0.08});
  EXPECT_DOUBLE_EQ(s.head().pan, 0.2);
  const SyntheticFrame b = s.render(100);
  EXPECT_FALSE(sameMat(a.left, b.left));
  EXPECT_DOUBLE_EQ(b.truth.head.pan, 0.2);
  // Turning right moves what is ahead to the left of the image.
  ASSERT_FALSE(a.truth.people.empty());
  EXPECT_LT(b.truth.people[0].head2d.x, a.truth.people[0].head2d.x - 50);
  // Vergence alone changes the zone, not the images.
  s.commandHead({0.2, -0.05, 0.2});
  const SyntheticFrame c = s.render(100);
  EXPECT_TRUE(sameMat(b.left, c.left));
  EXPECT_FALSE(sameMat(b.truth.inside, c.truth.inside));
}

TEST(SyntheticScene, BadOptionsAndPosesSayWhatToFix) {
  auto throwsWith = [](SceneOptions o, const char* what) {
    try {
      SyntheticScene s(o);
      ADD_FAILURE() << "no error for " << what;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  SceneOptions o;
  o.width = 0;
  throwsWith(o, "size");
  o = {};
  o.baselineM = -0.1;
  throwsWith(o, "baselineM");
  o = {};
  o.focalPx = -5;
  throwsWith(o, "focalPx");
  o = {};
  o.framesPerSecond = 0;
  throwsWith(o, "framesPerSecond");
  SyntheticScene s(SceneOptions{});
  EXPECT_THROW(s.commandHead({0, 0, -0.1}), Error);
  EXPECT_THROW(s.commandHead({std::nan(""), 0, 0.1}), Error);
  EXPECT_THROW(s.commandHead({2.0, 0, 0.1}), Error);
  EXPECT_THROW(s.render(-1), Error);
}

}  // namespace
}  // namespace horopter::synth
