// Head angles: atan2 on known 3-D points, the paper's formula, the limits,
// framing the hands, and the synthetic rig's actuation delay.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>

#include "horopter/app/interaction_stages.hpp"
#include "horopter/core/error.hpp"
#include "horopter/interaction/head_control.hpp"
#include "horopter/interaction/tracking.hpp"
#include "horopter/sim/closed_loop.hpp"

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

// A still point moves in the image as the head turns: the other way, by the
// turn's angle; and turning back puts it back.
TEST(HeadAngles, PixelAfterHeadTurnFollowsTheRotation) {
  const RectifiedGeometry rig{500, 320, 0.12, 240};
  const hw::HeadAngles ahead{0, 0, 0.06}, right{0.2, 0, 0.06}, down{0, 0.1, 0.06};
  const cv::Point2f centre(320, 240);
  // Unchanged pose: unchanged pixel.
  cv::Point2f p = pixelAfterHeadTurn(centre, 1.5, ahead, ahead, rig);
  EXPECT_NEAR(p.x, 320, 1e-3);
  EXPECT_NEAR(p.y, 240, 1e-3);
  // Far away, the turn about the rig's origin is a turn about the camera:
  // looking right by 0.2 rad moves the point f tan(0.2) to the left.
  p = pixelAfterHeadTurn(centre, 1e6, ahead, right, rig);
  EXPECT_NEAR(p.x, 320 - 500 * std::tan(0.2), 0.05);
  EXPECT_NEAR(p.y, 240, 1e-3);
  // Looking down moves it up.
  p = pixelAfterHeadTurn(centre, 1e6, ahead, down, rig);
  EXPECT_NEAR(p.x, 320, 1e-3);
  EXPECT_NEAR(p.y, 240 - 500 * std::tan(0.1), 0.05);
  // Near, the left camera's offset from the turning axis adds a little
  // parallax (about half a pixel at 1 m for this turn).
  const cv::Point2f nearPoint = pixelAfterHeadTurn(centre, 1.0, ahead, right, rig);
  EXPECT_GT(std::abs(nearPoint.x - (320 - 500 * std::tan(0.2))), 0.3);
  EXPECT_LT(std::abs(nearPoint.x - (320 - 500 * std::tan(0.2))), 1.5);
  // Far away, there and back again.
  const hw::HeadAngles turned{-0.3, 0.15, 0.06};
  const cv::Point2f there = pixelAfterHeadTurn({100, 400}, 1e6, ahead, turned, rig);
  const cv::Point2f back = pixelAfterHeadTurn(there, 1e6, turned, ahead, rig);
  EXPECT_GT(cv::norm(there - cv::Point2f(100, 400)), 100);
  EXPECT_NEAR(back.x, 100, 1e-2);
  EXPECT_NEAR(back.y, 400, 1e-2);
  // No geometry or depth: the pixel stays.
  p = pixelAfterHeadTurn({100, 400}, 0, ahead, right, rig);
  EXPECT_EQ(p, cv::Point2f(100, 400));
  p = pixelAfterHeadTurn({100, 400}, 1.5, ahead, right, RectifiedGeometry{});
  EXPECT_EQ(p, cv::Point2f(100, 400));
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

// The pan the head-control stage commands for a godfather whose head lies
// straight ahead (atan2 target 0) at `headX` in the image, with hands at
// `rightX` and `leftX` (NaN: not tracked).
double commandedPan(HeadControlOptions o, float headX, float rightX, float leftX) {
  o.gain = 1;
  o.deadbandRad = 0;
  o.maxRateRadPerS = 100;
  o.focalPx = 500;
  o.cx = 320;
  o.cy = 240;
  o.imageWidth = 640;
  std::optional<hw::HeadAngles> sent;
  auto stage = makeHeadControlStage(
      o,
      [](const StereoFrame&) {
        return std::optional<hw::HeadAngles>(hw::HeadAngles{0, 0, 0.06});
      },
      [&](std::int64_t, const std::optional<hw::HeadAngles>& c) { sent = c; });
  auto state = std::make_shared<TrackingState>();
  state->election = ElectionState::Godfather;
  state->head.tracked = state->head.observed = true;
  state->head.image = {headX, 200};
  state->head.rig = {0, 0, 1.5};  // on the axis: atan2 alone commands nothing
  if (!std::isnan(rightX)) {
    state->rightHand.tracked = true;
    state->rightHand.image = {rightX, 300};
  }
  if (!std::isnan(leftX)) {
    state->leftHand.tracked = true;
    state->leftHand.image = {leftX, 300};
  }
  Frame frame;
  frame.tracking = state;
  stage->process(frame);
  return sent ? sent->pan : 0.0;
}

TEST(HeadControlStage, FramesTheHandsExtentWithinALimit) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  HeadControlOptions o;
  o.frameHands = true;
  // No hands, or hands balanced about the face: the face alone decides.
  EXPECT_NEAR(commandedPan(o, 345, nan, nan), 0, 1e-9);
  EXPECT_NEAR(commandedPan(o, 345, 245, 445), 0, 1e-6);
  // The right hand stretched out to the image's left: the extent's middle
  // (130 + 385) / 2 = 257.5 goes where the face is, 87.5 px to the left.
  EXPECT_NEAR(commandedPan(o, 345, 130, 385), std::atan(-87.5 / 500), 1e-6);
  // Far out: at most a quarter of the width (160 px).
  EXPECT_NEAR(commandedPan(o, 345, -600, 385), std::atan(-160.0 / 500), 1e-6);
  o.maxHandShiftFraction = 0.1;
  EXPECT_NEAR(commandedPan(o, 345, -600, 385), std::atan(-64.0 / 500), 1e-6);
  o.frameHands = false;
  EXPECT_NEAR(commandedPan(o, 345, 130, 385), 0, 1e-9);
  EXPECT_FALSE(HeadControlOptions{}.frameHands) << "off by default";
  o.frameHands = true;
  o.maxHandShiftFraction = 0.6;
  EXPECT_THROW(commandedPan(o, 345, 130, 385), Error);
}

TEST(SyntheticRigHead, ACommandFromFrameNActsAtFrameNPlusTheDelay) {
  sim::SyntheticRigHead rig({0, 0, 0.06}, HeadControlOptions{}.limits, 3);
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
  EXPECT_THROW(sim::SyntheticRigHead({0, 0, 0}, HeadControlOptions{}.limits, 0), Error);
}

}  // namespace
}  // namespace horopter
