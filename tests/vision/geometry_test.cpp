// Horopter geometry: the threshold table against the Vieth-Mueller circle
// computed here independently (circumcircle of the two camera centres and the
// fixation point, intersected with each column's viewing ray).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "horopter/core/error.hpp"
#include "horopter/kernels/kernels.hpp"
#include "horopter/vision/geometry.hpp"
#include "test_support.hpp"

namespace horopter::test {
namespace {

constexpr int kMax = std::numeric_limits<std::int16_t>::max();

struct Circle {
  double x, z, r;
};

// The circle through three points of the (x, z) plane.
Circle circumcircle(double ax, double az, double bx, double bz, double cx, double cz) {
  const double d = 2 * (ax * (bz - cz) + bx * (cz - az) + cx * (az - bz));
  const double a2 = ax * ax + az * az, b2 = bx * bx + bz * bz, c2 = cx * cx + cz * cz;
  const double ux = (a2 * (bz - cz) + b2 * (cz - az) + c2 * (az - bz)) / d;
  const double uz = (a2 * (cx - bx) + b2 * (ax - cx) + c2 * (bx - ax)) / d;
  return {ux, uz, std::hypot(ax - ux, az - uz)};
}

// Depth s (> 0 in front) at which the ray of left column u, (s t, s), leaves
// the circle: the root of |(s t, s) - centre|^2 = r^2 other than the camera
// centre (s = 0).
double exitDepth(const Circle& c, const RectifiedGeometry& g, int u) {
  const double t = (u - g.cx) / g.focalPx;
  const double a = t * t + 1;
  const double b = -2 * (t * c.x + c.z);
  const double k = c.x * c.x + c.z * c.z - c.r * c.r;  // ~0: the camera is on the circle
  const double disc = std::sqrt(std::max(0.0, b * b - 4 * a * k));
  const double s1 = (-b + disc) / (2 * a), s2 = (-b - disc) / (2 * a);
  return std::abs(s1) > std::abs(s2) ? s1 : s2;
}

struct Scene {
  const char* what;
  RectifiedGeometry g;
  int width;
  FixationPoint fixation;
};

std::vector<Scene> scenes() {
  const RectifiedGeometry vga{500, 319.5, 0.1};
  const RectifiedGeometry unit{256, 127.5, 1.0};
  const RectifiedGeometry wide{100, 500, 1.0};
  return {
      {"midline fixation", vga, 640, {0.05, 1.0}},
      {"fixation to the right", vga, 640, {0.3, 2.0}},
      {"fixation to the left", vga, 640, {-0.2, 0.8}},
      {"near fixation", vga, 640, {0.05, 0.2}},
      // The circle's centre is behind the baseline: every ray of this field of
      // view leaves the circle behind the camera.
      {"fixation between the cameras, close: all rays leave behind", unit, 256, {0.4, 0.3}},
      {"from the CLI's defaults", unit, 256, fixationFromDisparity(unit, unit.cx, 26.0)},
      {"wide field, rays leaving behind", wide, 1000, {0.5, 1.0}},
  };
}

// A point on the circle seen in column u has disparity f B / s; the threshold
// is that disparity in 1/16 px, rounded up (ceil), or INT16_MAX for columns
// whose ray leaves the circle behind the camera.
TEST(Geometry, ThresholdIsDisparityOfCirclePointInEachColumn) {
  for (const Scene& s : scenes()) {
    SCOPED_TRACE(s.what);
    const auto table = horopterThresholds(s.g, s.width, s.fixation);
    ASSERT_EQ(table.size(), static_cast<std::size_t>(s.width));
    const Circle c = circumcircle(0, 0, s.g.baseline, 0, s.fixation.x, s.fixation.z);
    int behind = 0, finite = 0;
    for (int u = 0; u < s.width; ++u) {
      const double depth = exitDepth(c, s.g, u);
      const int t = table[u];
      if (depth <= 1e-9) {
        EXPECT_EQ(t, kMax) << "column " << u << " leaves the circle behind the camera";
        ++behind;
        continue;
      }
      // The point found is on the circle.
      const double x = depth * (u - s.g.cx) / s.g.focalPx;
      ASSERT_NEAR(std::hypot(x - c.x, depth - c.z), c.r, 1e-9 * (1 + c.r));
      const double d16 = 16.0 * s.g.focalPx * s.g.baseline / depth;
      if (d16 >= kMax) {
        EXPECT_EQ(t, kMax) << "column " << u;
      } else {
        EXPECT_GE(t, d16 - 1e-6) << "column " << u;
        EXPECT_LT(t, d16 + 1 + 1e-6) << "column " << u;
        ++finite;
      }
    }
    const bool allBehind = std::string(s.what).find("all rays") != std::string::npos;
    if (allBehind) {
      EXPECT_EQ(behind, s.width);
    } else {
      EXPECT_GT(finite, 0);
    }
    if (std::string(s.what).find("behind") != std::string::npos) {
      EXPECT_GT(behind, 0);
    }
  }
}

// Random points on every column's ray, classified inside / outside by their
// distance to the circle's centre, then run through horopterMask with their
// disparities: 255 exactly for the inside ones. Points closer than 1/16 px of
// disparity to the circle are left out (the table is rounded to 1/16 px).
TEST(Geometry, MaskMatchesInsideOfCircle) {
  for (const Scene& s : scenes()) {
    SCOPED_TRACE(s.what);
    const auto table = horopterThresholds(s.g, s.width, s.fixation);
    const Circle c = circumcircle(0, 0, s.g.baseline, 0, s.fixation.x, s.fixation.z);
    const int rows = 24;
    TestImage disparity(s.width, rows, PixelType::S16C1);
    std::vector<std::uint8_t> want(static_cast<std::size_t>(s.width) * rows, 0);
    std::vector<bool> use(want.size(), false);
    Rng rng(17);
    long inside = 0, outside = 0;
    for (int u = 0; u < s.width; ++u) {
      const double exit = exitDepth(c, s.g, u);
      const double exitD16 = exit > 0 ? 16 * s.g.focalPx * s.g.baseline / exit : 0;
      for (int y = 0; y < rows; ++y) {
        // Depths from 5% to 300% of the exit depth (or of the fixation depth).
        const double scale = exit > 0 ? exit : s.fixation.z;
        const double depth = scale * (0.05 + 2.95 * rng.uniform(0, 1 << 20) / double(1 << 20));
        const double d16 = 16 * s.g.focalPx * s.g.baseline / depth;
        const double x = depth * (u - s.g.cx) / s.g.focalPx;
        const bool in = std::hypot(x - c.x, depth - c.z) < c.r;
        disparity.at<std::int16_t>(u, y) =
            static_cast<std::int16_t>(std::min<double>(std::floor(d16), kMax - 1));
        const std::size_t i = static_cast<std::size_t>(y) * s.width + u;
        use[i] = d16 < kMax - 1 && (exit <= 0 || std::abs(d16 - exitD16) >= 1);
        want[i] = in ? 255 : 0;
        if (use[i]) (in ? inside : outside)++;
      }
    }
    TestImage mask(s.width, rows, PixelType::U8C1);
    horopterMask(disparity.view(), table, static_cast<std::int16_t>(-16), mask.view());
    long wrong = 0;
    for (int y = 0; y < rows; ++y) {
      for (int u = 0; u < s.width; ++u) {
        const std::size_t i = static_cast<std::size_t>(y) * s.width + u;
        if (!use[i]) continue;
        if (mask.at<std::uint8_t>(u, y) != want[i] && wrong++ < 5)
          ADD_FAILURE() << "column " << u << ", disparity " << disparity.at<std::int16_t>(u, y)
                        << "/16, threshold " << table[u] << ": mask "
                        << int(mask.at<std::uint8_t>(u, y)) << ", the point is "
                        << (want[i] ? "inside" : "outside");
      }
    }
    EXPECT_EQ(wrong, 0);
    if (std::string(s.what).find("all rays") == std::string::npos) {
      EXPECT_GT(inside, 0);
    }
    EXPECT_GT(outside, 0);
  }
}

// A fixation on the midline (x = B/2) is the circle's farthest point, and the
// circle is symmetric about the midline. The left camera is not on the
// midline, so the table is not symmetric about cx: the mirror of a circle
// point seen at column u (disparity D) is seen at u' = 2 cx + D - u with the
// same disparity. Checked with the table's rounding (+-1) between the two
// columns around u'.
TEST(Geometry, MidlineFixationGivesMirrorSymmetricTable) {
  const RectifiedGeometry g{500, 319.5, 0.1};
  const int width = 640;
  for (double z : {0.3, 1.0, 4.0}) {
    SCOPED_TRACE("fixation depth " + std::to_string(z));
    const FixationPoint f{g.baseline / 2, z};
    const auto table = horopterThresholds(g, width, f);
    const Circle c = circumcircle(0, 0, g.baseline, 0, f.x, f.z);
    // The apex: the least threshold is at the fixation's own column.
    const double fixD = g.focalPx * g.baseline / z;
    const double fixU = g.cx + g.focalPx * f.x / z;
    const int fixColumn = static_cast<int>(std::lround(fixU));
    const int least = *std::min_element(table.begin(), table.end());
    EXPECT_LE(table[fixColumn], least + 1) << "the fixation column holds the least threshold";
    EXPECT_NEAR(table[fixColumn], 16 * fixD, 1.5);
    int checked = 0;
    for (int u = 0; u < width; ++u) {
      const double depth = exitDepth(c, g, u);
      if (depth <= 0 || table[u] >= kMax) continue;
      const double d = g.focalPx * g.baseline / depth;
      const double mirror = 2 * g.cx + d - u;
      if (mirror < 0 || mirror > width - 1) continue;
      const int lo = static_cast<int>(std::floor(mirror)), hi = static_cast<int>(std::ceil(mirror));
      if (table[lo] >= kMax || table[hi] >= kMax) continue;
      EXPECT_GE(table[u], std::min(table[lo], table[hi]) - 1) << "column " << u << " vs " << mirror;
      EXPECT_LE(table[u], std::max(table[lo], table[hi]) + 1) << "column " << u << " vs " << mirror;
      ++checked;
    }
    EXPECT_GT(checked, width / 2);
  }
}

// Fixations mirrored about the midline, (B/2 + a, z) and (B/2 - a, z), give
// mirrored circles, so their tables are mirror images in the same sense.
TEST(Geometry, MirroredFixationsGiveMirroredTables) {
  const RectifiedGeometry g{400, 199.5, 0.2};
  const int width = 400;
  const FixationPoint right{0.1 + 0.15, 1.2}, left{0.1 - 0.15, 1.2};
  const auto tr = horopterThresholds(g, width, right);
  const auto tl = horopterThresholds(g, width, left);
  const Circle cr = circumcircle(0, 0, g.baseline, 0, right.x, right.z);
  int checked = 0;
  for (int u = 0; u < width; ++u) {
    const double depth = exitDepth(cr, g, u);
    if (depth <= 0 || tr[u] >= kMax) continue;
    const double mirror = 2 * g.cx + g.focalPx * g.baseline / depth - u;
    if (mirror < 0 || mirror > width - 1) continue;
    const int lo = static_cast<int>(std::floor(mirror)), hi = static_cast<int>(std::ceil(mirror));
    EXPECT_GE(tr[u], std::min(tl[lo], tl[hi]) - 1) << "column " << u;
    EXPECT_LE(tr[u], std::max(tl[lo], tl[hi]) + 1) << "column " << u;
    ++checked;
  }
  EXPECT_GT(checked, width / 2);
}

TEST(Geometry, FixationFromDisparityLiesOnItsRayAtThatDisparity) {
  const RectifiedGeometry g{700, 330.25, 0.12};
  for (double u : {0.0, 100.5, 330.25, 639.0}) {
    for (double d : {0.5, 7.0, 33.3, 200.0}) {
      const FixationPoint f = fixationFromDisparity(g, u, d);
      EXPECT_GT(f.z, 0);
      EXPECT_NEAR(g.cx + g.focalPx * f.x / f.z, u, 1e-9);
      EXPECT_NEAR(g.focalPx * g.baseline / f.z, d, 1e-9);
      // The fixation point is on the circle: its column's threshold is its disparity.
      const int column = static_cast<int>(u);
      if (column == u) {
        const auto table = horopterThresholds(g, 640, f);
        EXPECT_GE(table[column], 16 * d - 1e-6);
        EXPECT_LT(table[column], 16 * d + 1 + 1e-6);
      }
    }
  }
}

TEST(Geometry, NearerFixationRaisesTheThresholds) {
  const RectifiedGeometry g{500, 319.5, 0.1};
  std::vector<std::int16_t> previous;
  for (double z : {4.0, 2.0, 1.0, 0.5}) {
    const auto table = horopterThresholds(g, 640, {0.05, z});
    if (!previous.empty()) {
      for (int u = 0; u < 640; ++u)
        EXPECT_GE(table[u], previous[u]) << "column " << u << ", fixation depth " << z;
      EXPECT_GT(table[320], previous[320]);
    }
    previous = table;
  }
}

template <typename F>
void expectGeometryError(F&& f, const char* word) {
  try {
    f();
    ADD_FAILURE() << "no error; expected one mentioning " << word;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(word), std::string::npos)
        << "\"" << e.what() << "\" does not mention " << word;
  }
}

TEST(Geometry, BadGeometryThrows) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const FixationPoint fix{0.05, 1.0};
  for (double focal : {0.0, -500.0, nan, inf})
    expectGeometryError([&] { horopterThresholds({focal, 320, 0.1}, 640, fix); }, "focal");
  for (double baseline : {0.0, -0.1, nan})
    expectGeometryError([&] { horopterThresholds({500, 320, baseline}, 640, fix); }, "baseline");
  expectGeometryError([&] { horopterThresholds({500, nan, 0.1}, 640, fix); }, "principal point");
  for (double z : {0.0, -1.0, nan})
    expectGeometryError([&] { horopterThresholds({500, 320, 0.1}, 640, {0.05, z}); }, "z");
  expectGeometryError([&] { horopterThresholds({500, 320, 0.1}, 640, {nan, 1.0}); }, "fixation");
  for (int width : {0, -5})
    expectGeometryError([&] { horopterThresholds({500, 320, 0.1}, width, fix); }, "width");
  for (double d : {0.0, -3.0, nan})
    expectGeometryError([&] { fixationFromDisparity({500, 320, 0.1}, 320, d); }, "disparity");
  expectGeometryError([&] { fixationFromDisparity({0, 320, 0.1}, 320, 10); }, "focal");
}

}  // namespace
}  // namespace horopter::test
