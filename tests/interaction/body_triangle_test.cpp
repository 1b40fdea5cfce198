// The body triangle: incentre, perimeter and head angle on known points.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "horopter/interaction/detection.hpp"

namespace horopter {
namespace {

TEST(BodyTriangle, RightTriangleThreeFourFive) {
  // Right angle at the head; legs 3 and 4, hypotenuse 5: the inradius is
  // (3 + 4 - 5) / 2 = 1, so the incentre sits 1 from both legs.
  const BodyTriangle t = bodyTriangle({0, 0}, {3, 0}, {0, 4});
  EXPECT_FALSE(t.degenerate);
  EXPECT_NEAR(t.perimeter, 12.0, 1e-9);
  EXPECT_NEAR(t.incentre.x, 1.0, 1e-6);
  EXPECT_NEAR(t.incentre.y, 1.0, 1e-6);
  EXPECT_NEAR(t.headAngleRad, std::numbers::pi / 2, 1e-9);
}

TEST(BodyTriangle, EquilateralIncentreIsTheCentroid) {
  const float h = static_cast<float>(10 * std::sqrt(3.0));
  const BodyTriangle t = bodyTriangle({10, 0}, {20, h}, {0, h});
  EXPECT_NEAR(t.perimeter, 60.0, 1e-4);
  EXPECT_NEAR(t.incentre.x, 10.0, 1e-4);
  EXPECT_NEAR(t.incentre.y, 2 * h / 3, 1e-4);
  EXPECT_NEAR(t.headAngleRad, std::numbers::pi / 3, 1e-6);
}

TEST(BodyTriangle, IncentreIsEquidistantFromTheSides) {
  const cv::Point2f a(320, 100), b(420, 330), c(200, 280);
  const BodyTriangle t = bodyTriangle(a, b, c);
  auto distance = [&](cv::Point2f p, cv::Point2f q) {
    const cv::Point2f d = q - p, r = t.incentre - p;
    return std::abs(d.x * r.y - d.y * r.x) / std::hypot(d.x, d.y);
  };
  const double r = distance(a, b);
  EXPECT_NEAR(distance(b, c), r, 1e-3);
  EXPECT_NEAR(distance(c, a), r, 1e-3);
  // The area is r * perimeter / 2.
  const double area = 0.5 * std::abs((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
  EXPECT_NEAR(r * t.perimeter / 2, area, 0.05);
}

TEST(BodyTriangle, CollinearPointsAreDegenerate) {
  const BodyTriangle t = bodyTriangle({0, 0}, {1, 1}, {2, 2});
  EXPECT_TRUE(t.degenerate);
  EXPECT_NEAR(t.incentre.x, 1.0, 1e-6);
  EXPECT_NEAR(t.perimeter, 4 * std::sqrt(2.0), 1e-6);
  const BodyTriangle same = bodyTriangle({5, 5}, {5, 5}, {5, 5});
  EXPECT_TRUE(same.degenerate);
  EXPECT_EQ(same.perimeter, 0);
}

}  // namespace
}  // namespace horopter
