// Head angles: atan2 on known 3-D points, the paper's formula, the limits,
// and the synthetic rig's actuation delay.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "horopter/error.hpp"
#include "horopter/head_control.hpp"

namespace horopter {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(HeadAngles, Atan2CentresKnownPoints) {
  const hw::HeadAngles zero{};
  hw::HeadAngles a = anglesToCentre({0, 0, 2}, zero);
  EXPECT_NEAR(a.pan, 0, 1e-12);
  EXPECT_NEAR(a.tilt, 0, 1e-12);
  a = anglesToCentre({1, 0, 1}, zero);  // 45 degrees to the right
  EXPECT_NEAR(a.pan, kPi / 4, 1e-6);
  EXPECT_NEAR(a.tilt, 0, 1e-6);
  a = anglesToCentre({0, -1, std::sqrt(3.0f)}, zero);  // 30 degrees up: tilt is negative
  EXPECT_NEAR(a.pan, 0, 1e-6);
  EXPECT_NEAR(a.tilt, -kPi / 6, 1e-6);
  a = anglesToCentre({1, 1, 1}, zero);  // the tilt is measured from the horizontal distance
  EXPECT_NEAR(a.pan, kPi / 4, 1e-6);
  EXPECT_NEAR(a.tilt, std::atan2(1.0, std::sqrt(2.0)), 1e-6);
}

TEST(HeadAngles, Atan2IsAbsoluteWhateverThePose) {
  // A point straight ahead of a turned head keeps the head where it is; a
  // point on the base's axis brings it back to zero.
  const hw::HeadAngles pose{0.3, -0.2, 0.06};
  hw::HeadAngles a = anglesToCentre({0, 0, 1.5}, pose);
  EXPECT_NEAR(a.pan, 0.3, 1e-6);
  EXPECT_NEAR(a.tilt, -0.2, 1e-6);
  EXPECT_EQ(a.vergence, 0.06);
  // The base's forward axis, expressed in the turned rig frame.
  const double cp = std::cos(0.3), sp = std::sin(0.3), ct = std::cos(-0.2), st = std::sin(-0.2);
  // rig = Rx(tilt)^T Ry(pan)^T (0, 0, 1)
  const double x1 = -sp, z1 = cp;
  const cv::Point3f rig(static_cast<float>(x1), static_cast<float>(-st * z1),
                        static_cast<float>(ct * z1));
  a = anglesToCentre(rig, pose);
  EXPECT_NEAR(a.pan, 0, 1e-6);
  EXPECT_NEAR(a.tilt, 0, 1e-6);
}

TEST(HeadAngles, PaperFormula) {
  // phi = d * lambda = 1: the pinhole angle of the pixel.
  EXPECT_NEAR(paperAngle(100, 500, 2.0, 0.5), std::atan(100.0 / 500.0), 1e-12);
  // phi = 2 halves the tangent.
  EXPECT_NEAR(paperAngle(100, 500, 2.0, 1.0), std::atan(100.0 / 1000.0), 1e-12);
  EXPECT_NEAR(paperAngle(-50, 500, 1.0, 1.0), -std::atan(0.1), 1e-12);
  EXPECT_THROW(paperAngle(10, 0, 1, 1), Error);
  EXPECT_THROW(paperAngle(10, 500, 1, 0), Error);
}

TEST(HeadAngles, CommandIsDeadBandedRateLimitedAndClamped) {
  HeadControlOptions o;
  o.gain = 1;
  o.deadbandRad = 0.02;
  o.maxRateRadPerS = 0.6;
  o.framesPerSecond = 30;  // at most 0.02 rad per frame
  const hw::HeadAngles pose{0.1, 0.0, 0.06};
  hw::HeadAngles c = limitCommand(pose, {0.11, 0.005, 0}, o);
  EXPECT_EQ(c.pan, 0.1) << "inside the dead band";
  EXPECT_EQ(c.tilt, 0.0);
  EXPECT_EQ(c.vergence, 0.06);
  c = limitCommand(pose, {0.5, -0.3, 0}, o);
  EXPECT_NEAR(c.pan, 0.12, 1e-12);
  EXPECT_NEAR(c.tilt, -0.02, 1e-12);
  o.maxRateRadPerS = 100;
  c = limitCommand(pose, {3.0, -3.0, 0}, o);
  EXPECT_EQ(c.pan, o.limits.panMax);
  EXPECT_EQ(c.tilt, o.limits.tiltMin);
  o.gain = 0.5;
  c = limitCommand(pose, {0.3, 0.0, 0}, o);
  EXPECT_NEAR(c.pan, 0.2, 1e-12);
}

TEST(SyntheticRigHead, ACommandFromFrameNActsAtFrameNPlusTheDelay) {
  SyntheticRigHead rig({0, 0, 0.06}, HeadControlOptions{}.limits, 3);
  for (int frame = 0; frame < 3; ++frame)
    EXPECT_EQ(rig.poseForFrame(frame).pan, 0) << frame;
  rig.post(0, std::nullopt);
  rig.post(1, hw::HeadAngles{0.2, 0.1, 0});
  rig.post(2, std::nullopt);
  EXPECT_EQ(rig.poseForFrame(3).pan, 0) << "frame 0 posted nothing";
  const hw::HeadAngles p = rig.poseForFrame(4);
  EXPECT_EQ(p.pan, 0.2);
  EXPECT_EQ(p.tilt, 0.1);
  EXPECT_EQ(p.vergence, 0.06) << "the rig keeps its vergence";
  // Frame 6 waits for frame 3's post, which never comes.
  EXPECT_THROW(rig.poseForFrame(6, std::chrono::milliseconds(20)), Error);
  EXPECT_THROW(rig.post(2, std::nullopt), Error) << "out of order";
  EXPECT_THROW(SyntheticRigHead({0, 0, 0}, HeadControlOptions{}.limits, 0), Error);
}

}  // namespace
}  // namespace horopter
