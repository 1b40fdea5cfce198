// Vergence geometry in the cyclopean frame: the fixation helpers, the
// Vieth-Mueller circle (inscribed angle theorem), the threshold table against
// brute force and against random 3-D points through horopterMask, and the
// degenerate inputs.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "horopter/core/error.hpp"
#include "horopter/kernels/kernels.hpp"
#include "horopter/vision/geometry.hpp"
#include "test_support.hpp"

namespace horopter::test {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr int kMax = std::numeric_limits<std::int16_t>::max();

double deg(double d) {
  return d * kPi / 180.0;
}

double uniform(Rng& rng, double lo, double hi) {
  return lo + (hi - lo) * rng.uniform(0, 1 << 24) / double(1 << 24);
}

struct Head {
  const char* what;
  RectifiedGeometry g;
  int width;
  Eigen::Vector3d fixation;
};

std::vector<Head> heads() {
  const RectifiedGeometry vga{520, 319.5, 0.12, 239.5};
  const RectifiedGeometry calib{518.86, 337.67, 0.0834, 243.92};  // like opencv-doc's rig
  const RectifiedGeometry narrow{1400, 640.25, 0.3, 360};
  return {
      {"symmetric vergence 6 deg", vga, 640, fixationFromVergence(vga.baseline, deg(6))},
      {"symmetric vergence 30 deg (near)", vga, 640, fixationFromVergence(vga.baseline, deg(30))},
      {"pans 5 / -1 deg", vga, 640, fixationFromPanAngles(vga.baseline, deg(5), deg(-1))},
      {"pans 2 / 1 deg (far, right)", calib, 640,
       fixationFromPanAngles(calib.baseline, deg(2), deg(1))},
      {"pans -3 / -9 deg (left)", calib, 640,
       fixationFromPanAngles(calib.baseline, deg(-3), deg(-9))},
      {"distance 1.2", calib, 640, fixationAtDistance(calib.baseline, 1.2)},
      {"distance 0.3, narrow lens", narrow, 1280, fixationAtDistance(narrow.baseline, 0.3)},
      {"distance 8", narrow, 1280, fixationAtDistance(narrow.baseline, 8.0)},
  };
}

// The left camera's ray of column u meets the circle (centre (0, zc), radius
// r) at the camera and at depth s: (-B/2 + s t, s) on the circle, solved here
// as a general quadratic (not the table's closed form).
double exitDepth(const RectifiedGeometry& g, const ViethMuellerCircle& c, double u) {
  const double t = (u - g.cx) / g.focalPx;
  const double x0 = -0.5 * g.baseline;
  const double a = t * t + 1, b = 2 * (x0 * t - c.centreZ);
  const double k = x0 * x0 + c.centreZ * c.centreZ - c.radius * c.radius;
  const double disc = std::sqrt(std::max(0.0, b * b - 4 * a * k));
  const double s1 = (-b + disc) / (2 * a), s2 = (-b - disc) / (2 * a);
  return std::abs(s1) > std::abs(s2) ? s1 : s2;
}

TEST(VergenceGeometry, PointsOnTheCircleSubtendTheFixationsVergence) {
  for (const Head& h : heads()) {
    SCOPED_TRACE(h.what);
    const double b = h.g.baseline;
    const ViethMuellerCircle c = viethMuellerCircle(b, h.fixation);
    // The circle passes through both cameras and the fixation.
    EXPECT_NEAR(std::hypot(0.5 * b, c.centreZ), c.radius, 1e-12 * c.radius);
    EXPECT_NEAR(std::hypot(h.fixation.x(), h.fixation.z() - c.centreZ), c.radius, 1e-9 * c.radius);
    const double vergence = vergenceAngleAt(b, h.fixation);
    // Every point of the arc in front of the cameras (z > 0, in the plane of
    // the circle) sees the baseline under the same angle (inscribed angle
    // theorem).
    const double start = std::atan2(-c.centreZ, 0.5 * b);  // angle of the right camera
    for (int i = 1; i < 50; ++i) {
      const double phi = start + (kPi - 2 * start) * i / 50.0;
      const Eigen::Vector3d p(c.radius * std::cos(phi), 0, c.centreZ + c.radius * std::sin(phi));
      ASSERT_GT(p.z(), 0);
      EXPECT_NEAR(vergenceAngleAt(b, p), vergence, 1e-9) << "point " << i;
      // A point a little inside sees a larger angle, a little outside a smaller one.
      const Eigen::Vector3d in(0.99 * p.x(), p.y(), c.centreZ + 0.99 * (p.z() - c.centreZ));
      const Eigen::Vector3d out(1.01 * p.x(), p.y(), c.centreZ + 1.01 * (p.z() - c.centreZ));
      EXPECT_GT(vergenceAngleAt(b, in), vergence);
      EXPECT_LT(vergenceAngleAt(b, out), vergence);
      EXPECT_TRUE(insideZone(c, in));
      EXPECT_FALSE(insideZone(c, out));
    }
  }
}

TEST(VergenceGeometry, FixationHelpersAgree) {
  const double b = 0.1;
  for (double v : {0.5, 4.0, 20.0, 90.0, 150.0}) {
    const Eigen::Vector3d f = fixationFromVergence(b, deg(v));
    EXPECT_NEAR(f.x(), 0, 1e-15);
    EXPECT_NEAR(f.z(), 0.5 * b / std::tan(deg(v) / 2), 1e-12 * f.z());
    EXPECT_NEAR(vergenceAngleAt(b, f), deg(v), 1e-9);
    // The same fixation from symmetric pans and from the distance.
    const Eigen::Vector3d p = fixationFromPanAngles(b, deg(v) / 2, -deg(v) / 2);
    EXPECT_LT((p - f).norm(), 1e-12 * f.z());
    EXPECT_LT((fixationAtDistance(b, f.z()) - f).norm(), 1e-12 * f.z());
  }
  // Asymmetric pans: the fixation is on both rays and the vergence is the
  // difference of the pans.
  for (const auto& [l, r] : {std::pair{10.0, -2.0}, {3.0, 1.0}, {-4.0, -20.0}, {60.0, 10.0}}) {
    const Eigen::Vector3d f = fixationFromPanAngles(b, deg(l), deg(r));
    const Eigen::Vector3d fromLeft = f - Eigen::Vector3d(-0.5 * b, 0, 0);
    const Eigen::Vector3d fromRight = f - Eigen::Vector3d(0.5 * b, 0, 0);
    EXPECT_NEAR(std::atan2(fromLeft.x(), fromLeft.z()), deg(l), 1e-12);
    EXPECT_NEAR(std::atan2(fromRight.x(), fromRight.z()), deg(r), 1e-12);
    EXPECT_NEAR(vergenceAngleAt(b, f), deg(l - r), 1e-9);
  }
}

TEST(VergenceGeometry, ClosestApproachOfTheAxes) {
  const double b = 0.2;
  // Axes that meet at p: the fixation is p.
  const Eigen::Vector3d p(0.3, -0.1, 1.7);
  const Ray left{{-0.5 * b, 0, 0}, p - Eigen::Vector3d(-0.5 * b, 0, 0)};
  const Ray right{{0.5 * b, 0, 0}, 3.0 * (p - Eigen::Vector3d(0.5 * b, 0, 0))};
  EXPECT_LT((fixationFromAxes(left, right) - p).norm(), 1e-12);
  // Skew axes symmetric under (x, y, z) -> (-x, -y, z): left (a, e, 1) from
  // (-B/2, 0, 0), right (-a, -e, 1) from (B/2, 0, 0). Their common
  // perpendicular is at range s = B a / (2 (a^2 + e^2)) on both, its midpoint
  // on the z axis at z = s.
  for (const auto& [a, e] : {std::pair{0.05, 0.01}, {0.2, 0.05}, {0.01, 0.002}}) {
    const Ray l{{-0.5 * b, 0, 0}, {a, e, 1}}, r{{0.5 * b, 0, 0}, {-a, -e, 1}};
    const Eigen::Vector3d f = fixationFromAxes(l, r);
    const double s = b * a / (2 * (a * a + e * e));
    EXPECT_NEAR(f.x(), 0, 1e-12);
    EXPECT_NEAR(f.y(), 0, 1e-12);
    EXPECT_NEAR(f.z(), s, 1e-12 * s);
  }
}

// A pixel's 3-D point projects back to that pixel in the left image and to
// (u - d, v) in the right one.
TEST(VergenceGeometry, PointOfAPixelReprojects) {
  const RectifiedGeometry g{520, 319.5, 0.12, 239.5};
  Rng rng(5);
  for (int i = 0; i < 200; ++i) {
    const double u = uniform(rng, 0, 639), v = uniform(rng, 0, 479), d = uniform(rng, 0.2, 90);
    const Eigen::Vector3d p = pointFromPixel(g, u, v, d);
    EXPECT_NEAR(p.z(), depthFromDisparity(g, d), 1e-12 * p.z());
    EXPECT_NEAR(p.z(), g.focalPx * g.baseline / d, 1e-12 * p.z());
    EXPECT_NEAR(g.cx + g.focalPx * (p.x() + 0.5 * g.baseline) / p.z(), u, 1e-9);
    EXPECT_NEAR(g.cx + g.focalPx * (p.x() - 0.5 * g.baseline) / p.z(), u - d, 1e-9);
    EXPECT_NEAR(g.cy + g.focalPx * p.y() / p.z(), v, 1e-9);
  }
}

// Per column, the least disparity D (1/16 px) whose point on the column's ray
// is inside the circle or on it, found by trying every D: the table must hold
// exactly that (INT16_MAX where none is), except where 16 x the circle's
// disparity is within 1e-6 of an integer (a floating-point tie).
TEST(VergenceGeometry, TableEqualsBruteForcePerColumn) {
  for (const Head& h : heads()) {
    SCOPED_TRACE(h.what);
    const RectifiedGeometry& g = h.g;
    const ViethMuellerCircle c = viethMuellerCircle(g.baseline, h.fixation);
    std::vector<std::int16_t> table(static_cast<std::size_t>(h.width));
    horopterThresholds(g, c, table);
    const int step = h.width > 640 ? 4 : 2;  // every 2nd or 4th column keeps this fast
    int finite = 0;
    for (int u = 0; u < h.width; u += step) {
      int least = kMax;
      // The inside of the ray is an interval of depths from the camera, so of
      // disparities up to infinity: scan down from the largest D.
      for (int d = kMax - 1; d >= 1; --d) {
        const Eigen::Vector3d p = pointFromPixel(g, u, 0, d / 16.0);
        if (std::hypot(p.x(), p.z() - c.centreZ) > c.radius) break;
        least = d;
      }
      if (least == kMax - 1 && table[u] == kMax) continue;  // only the int16 clamp differs
      const double exit = exitDepth(g, c, u);
      const double circle16 = exit > 0 ? 16 * g.focalPx * g.baseline / exit : 0;
      if (exit > 0 && std::abs(circle16 - std::round(circle16)) < 1e-6) {
        EXPECT_LE(std::abs(table[u] - least), 1) << "column " << u;
      } else {
        EXPECT_EQ(table[u], least) << "column " << u << ", circle disparity " << circle16 / 16;
      }
      if (least < kMax) ++finite;
    }
    EXPECT_GT(finite, 0);
  }
}

// Random 3-D points in front of the head, seen at a random left column: their
// disparity as the matcher reports it (rounded to 1/16 px) goes through
// horopterMask with the table; the mask must say inside exactly for the
// points inside the circle, except within 1/32 px of disparity of the circle
// (where rounding to 1/16 px may move a point across).
TEST(VergenceGeometry, RandomPointsAreClassifiedThroughDisparityAndTable) {
  for (const Head& h : heads()) {
    SCOPED_TRACE(h.what);
    const RectifiedGeometry& g = h.g;
    const ViethMuellerCircle c = viethMuellerCircle(g.baseline, h.fixation);
    std::vector<std::int16_t> table(static_cast<std::size_t>(h.width));
    horopterThresholds(g, c, table);
    const int rows = 40;
    TestImage disparity(h.width, rows, PixelType::S16C1);
    std::vector<int> want(static_cast<std::size_t>(h.width) * rows, -1);  // -1: in the band
    Rng rng(11);
    const double far = 3 * std::max(h.fixation.z(), c.centreZ + c.radius);
    long inside = 0, outside = 0;
    for (int y = 0; y < rows; ++y) {
      for (int u = 0; u < h.width; ++u) {
        // A point on the ray of column u at a random depth, then tested in 3-D.
        const double z = uniform(rng, 0.02 * far, far);
        const double d = g.focalPx * g.baseline / z;
        const Eigen::Vector3d p = pointFromPixel(g, u, uniform(rng, 0, 479), d);
        const long d16 = std::lround(16 * d);
        disparity.at<std::int16_t>(u, y) = static_cast<std::int16_t>(std::min<long>(d16, kMax));
        const double exit = exitDepth(g, c, u);
        const double circleD = exit > 0 ? g.focalPx * g.baseline / exit : 0;
        if (d16 >= kMax || (exit > 0 && std::abs(d - circleD) <= 1.0 / 32)) continue;
        const bool in = insideZone(c, p);
        want[static_cast<std::size_t>(y) * h.width + u] = in ? 255 : 0;
        (in ? inside : outside)++;
      }
    }
    TestImage mask(h.width, rows, PixelType::U8C1);
    horopterMask(disparity.view(), table, static_cast<std::int16_t>(-16), mask.view());
    long wrong = 0;
    for (int y = 0; y < rows; ++y) {
      for (int u = 0; u < h.width; ++u) {
        const int w = want[static_cast<std::size_t>(y) * h.width + u];
        if (w < 0 || mask.at<std::uint8_t>(u, y) == w) continue;
        if (wrong++ < 5)
          ADD_FAILURE() << "column " << u << ": disparity " << disparity.at<std::int16_t>(u, y)
                        << "/16, threshold " << table[u] << ", the point is "
                        << (w ? "inside" : "outside");
      }
    }
    EXPECT_EQ(wrong, 0);
    EXPECT_GT(inside, 100);
    EXPECT_GT(outside, 100);
  }
}

// The cheap per-frame path (circle, span) equals the older left-frame entry
// point, and a head that moves gives a new table each frame.
TEST(VergenceGeometry, PerFrameTableMatchesTheLeftFrameEntryPoint) {
  const RectifiedGeometry g{520, 319.5, 0.12, 239.5};
  std::vector<std::int16_t> table(640), previous;
  for (int frame = 0; frame < 20; ++frame) {
    const Eigen::Vector3d f =
        fixationFromPanAngles(g.baseline, deg(2 + 0.3 * frame), deg(-2 + 0.1 * frame));
    horopterThresholds(g, viethMuellerCircle(g.baseline, f), table);
    EXPECT_EQ(table, horopterThresholds(g, 640, toLeftCameraFrame(g, f))) << "frame " << frame;
    if (!previous.empty()) {
      EXPECT_NE(table, previous) << "frame " << frame;
    }
    previous = table;
  }
}

TEST(VergenceGeometry, ZoneExtent) {
  const double b = 0.0834;
  for (double distance : {0.5, 1.2, 3.0}) {
    const ViethMuellerCircle c = viethMuellerCircle(b, fixationAtDistance(b, distance));
    const ZoneExtent e = zoneExtent(b, c);
    EXPECT_NEAR(e.farOnAxis, distance, 1e-12 * distance);  // the fixation is the far apex
    EXPECT_NEAR(zoneWidthAt(c, distance), 0, 1e-6);
    EXPECT_NEAR(e.widest, 2 * c.radius, 1e-12);
    EXPECT_NEAR(zoneWidthAt(c, 0), b, 1e-12);  // the chord through both cameras
    EXPECT_NEAR(e.farOnCamera, 2 * c.centreZ, 1e-12);
    // The optical axis of the left camera (x = -B/2) leaves the circle there.
    EXPECT_NEAR(std::hypot(-0.5 * b, e.farOnCamera - c.centreZ), c.radius, 1e-12);
  }
}

template <typename F>
void expectError(F&& f, const std::string& word) {
  try {
    f();
    ADD_FAILURE() << "no error; expected one mentioning " << word;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(word), std::string::npos)
        << "\"" << e.what() << "\" does not mention " << word;
  }
}

TEST(VergenceGeometry, DegenerateInputIsAClearError) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const double b = 0.1;
  // Fixation at infinity: parallel axes.
  expectError([&] { fixationFromVergence(b, 0.0); }, "infinity");
  expectError([&] { fixationFromPanAngles(b, deg(3), deg(3)); }, "infinity");
  expectError(
      [&] {
        fixationFromAxes({{-b / 2, 0, 0}, {0, 0, 1}}, {{b / 2, 0, 0}, {0, 0, 2}});
      },
      "parallel");
  expectError([&] { viethMuellerCircle(b, {0, 0, inf}); }, "finite");
  expectError([&] { fixationAtDistance(b, inf); }, "distance");
  // Behind the cameras: diverging axes, negative depths.
  expectError([&] { fixationFromVergence(b, -deg(2)); }, "vergence");
  expectError([&] { fixationFromVergence(b, kPi); }, "vergence");
  expectError([&] { fixationFromPanAngles(b, deg(-2), deg(3)); }, "do not cross");
  expectError([&] { fixationFromPanAngles(b, deg(95), deg(3)); }, "90 deg");
  expectError(
      [&] {
        fixationFromAxes({{-b / 2, 0, 0}, {-0.1, 0, 1}}, {{b / 2, 0, 0}, {0.1, 0, 1}});
      },
      "behind");
  expectError([&] { viethMuellerCircle(b, {0.2, 0, -1.0}); }, "behind");
  expectError([&] { viethMuellerCircle(b, {0.2, 0, 0.0}); }, "behind");
  expectError([&] { fixationAtDistance(b, 0.0); }, "distance");
  // Zero and non-finite baselines.
  for (double bad : {0.0, -0.1, nan, inf}) {
    expectError([&] { fixationFromVergence(bad, deg(5)); }, "baseline");
    expectError([&] { fixationFromPanAngles(bad, deg(5), 0); }, "baseline");
    expectError([&] { fixationAtDistance(bad, 1.0); }, "baseline");
    expectError([&] { viethMuellerCircle(bad, {0, 0, 1}); }, "baseline");
  }
  expectError(
      [&] {
        fixationFromAxes({{0, 0, 0}, {0.1, 0, 1}}, {{0, 0, 0}, {-0.1, 0, 1}});
      },
      "baseline");
  // Non-finite values.
  expectError([&] { fixationFromVergence(b, nan); }, "vergence");
  expectError([&] { fixationFromPanAngles(b, nan, 0); }, "pan");
  expectError(
      [&] {
        fixationFromAxes({{-b / 2, 0, 0}, {nan, 0, 1}}, {{b / 2, 0, 0}, {0, 0, 1}});
      },
      "finite");
  expectError([&] { viethMuellerCircle(b, {nan, 0, 1}); }, "finite");
  const RectifiedGeometry g{520, 319.5, b, 239.5};
  expectError([&] { depthFromDisparity(g, 0.0); }, "disparity");
  expectError([&] { pointFromPixel(g, 10, 10, nan); }, "disparity");
  expectError([&] { pointFromPixel(g, nan, 10, 3); }, "finite");
  expectError([&] { depthFromDisparity({520, 319.5, 0.0, 0}, 3.0); }, "baseline");
  // A circle built for another baseline, or an empty table.
  const ViethMuellerCircle other = viethMuellerCircle(0.3, {0, 0, 1});
  std::vector<std::int16_t> table(640);
  expectError([&] { horopterThresholds(g, other, table); }, "camera centres");
  expectError([&] { horopterThresholds(g, viethMuellerCircle(b, {0, 0, 1}), {}); }, "width");
}

}  // namespace
}  // namespace horopter::test
