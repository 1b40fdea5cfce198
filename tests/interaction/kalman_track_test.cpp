// The constant-velocity Kalman track on known trajectories, and its gate.
#include <gtest/gtest.h>

#include <cmath>

#include "horopter/core/error.hpp"
#include "horopter/interaction/kalman_track.hpp"

namespace horopter {
namespace {

constexpr double kDt = 1.0 / 30;

TEST(ConstantVelocityTrack, ConvergesToAStraightLineAtConstantSpeed) {
  // x = 100 + 120 t, y = 200 - 60 t, exact measurements.
  ConstantVelocityTrack track({100, 200}, 0, KalmanOptions{});
  for (int i = 1; i <= 60; ++i) {
    const double t = i * kDt;
    track.predict(t);
    track.update(cv::Point2f(static_cast<float>(100 + 120 * t), static_cast<float>(200 - 60 * t)));
  }
  EXPECT_NEAR(track.velocity().x, 120, 3);
  EXPECT_NEAR(track.velocity().y, -60, 3);
  // Coasting half a second follows the line.
  track.predict(2.5);
  EXPECT_NEAR(track.position().x, 100 + 120 * 2.5, 3);
  EXPECT_NEAR(track.position().y, 200 - 60 * 2.5, 3);
}

TEST(ConstantVelocityTrack, SmoothsNoiseOnAStationaryPoint) {
  cv::RNG rng(3);
  ConstantVelocityTrack track({50, 50}, 0, KalmanOptions{200, 4, 50, 13.8, 0});
  double raw2 = 0, filtered2 = 0;
  for (int i = 1; i <= 120; ++i) {
    track.predict(i * kDt);
    const cv::Point2f z(static_cast<float>(50 + rng.gaussian(4)),
                        static_cast<float>(50 + rng.gaussian(4)));
    track.update(z);
    if (i > 30) {
      raw2 += std::pow(z.x - 50.0, 2) + std::pow(z.y - 50.0, 2);
      filtered2 += std::pow(track.position().x - 50.0, 2) + std::pow(track.position().y - 50.0, 2);
    }
  }
  EXPECT_LT(filtered2, 0.5 * raw2) << "the filtered position is much closer than the measurements";
}

TEST(ConstantVelocityTrack, FollowsACircleWithinAFewPixels) {
  // A hand circling at 0.9 Hz with radius 40 px, measured every frame.
  ConstantVelocityTrack track({340, 200}, 0, KalmanOptions{});
  double worst = 0;
  for (int i = 1; i <= 90; ++i) {
    const double t = i * kDt, a = 2 * CV_PI * 0.9 * t;
    const cv::Point2f z(static_cast<float>(300 + 40 * std::cos(a)),
                        static_cast<float>(200 + 40 * std::sin(a)));
    track.predict(t);
    if (i > 15) worst = std::max(worst, static_cast<double>(cv::norm(track.position() - z)));
    EXPECT_TRUE(track.inGate(z)) << "frame " << i;
    track.update(z);
  }
  EXPECT_LT(worst, 15.0) << "the prediction one frame ahead";
}

TEST(ConstantVelocityTrack, GateRejectsFarDetectionsAndWidensWhileCoasting) {
  ConstantVelocityTrack track({100, 100}, 0, KalmanOptions{1500, 4, 300, 13.8, 12});
  for (int i = 1; i <= 30; ++i) {
    track.predict(i * kDt);
    track.update({100, 100});
  }
  track.predict(31 * kDt);
  EXPECT_TRUE(track.inGate({105, 103}));
  EXPECT_FALSE(track.inGate({160, 100}));
  EXPECT_GT(track.distance2({130, 100}), track.distance2({120, 100}));
  // After half a second without detections the same offset is inside the gate.
  const double before = track.distance2({130, 100});
  track.predict(46 * kDt);
  EXPECT_LT(track.distance2({130, 100}), before);
}

TEST(ConstantVelocityTrack, BadNoisesAreAnError) {
  EXPECT_THROW(ConstantVelocityTrack({0, 0}, 0, KalmanOptions{0, 4, 300, 13.8, 12}), Error);
  EXPECT_THROW(ConstantVelocityTrack({0, 0}, 0, KalmanOptions{1500, -1, 300, 13.8, 12}), Error);
}

}  // namespace
}  // namespace horopter
