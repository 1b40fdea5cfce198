// The behaviour layer: Table II, one action per movement (cool-down), stop
// honoured always, velocity profiles that integrate to the intended motion.
#include <gtest/gtest.h>

#include <cmath>

#include "horopter/core/error.hpp"
#include "horopter/movement/behaviour.hpp"

namespace horopter {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDt = 1.0 / 30;

struct Integrated {
  double angle = 0, distance = 0;
  int starts = 0;
  double endS = -1;
};

// Runs the behaviour from t = 0 for `seconds`, with `decisions` at given frames.
Integrated runFor(Behaviour& b, double seconds,
                  std::vector<std::pair<int, MovementClass>> decisions, int firstFrame = 0) {
  Integrated r;
  const int frames = static_cast<int>(seconds / kDt);
  for (int i = firstFrame; i < firstFrame + frames; ++i) {
    std::optional<MovementClass> d;
    for (auto& [f, m] : decisions)
      if (f == i) d = m;
    const auto out = b.update(i * kDt, d, LmaFeatures{});
    r.angle += out.base.angular * kDt;
    r.distance += out.base.linear * kDt;
    r.starts += out.started ? 1 : 0;
    if (out.action != RobotAction::None) r.endS = i * kDt;
  }
  return r;
}

TEST(Behaviour, TableTwo) {
  EXPECT_EQ(actionFor(MovementClass::Circle), RobotAction::Rotate360);
  EXPECT_EQ(actionFor(MovementClass::Pointing), RobotAction::Acknowledge);
  EXPECT_EQ(actionFor(MovementClass::WaveLeft), RobotAction::StepLeft);
  EXPECT_EQ(actionFor(MovementClass::WaveRight), RobotAction::StepRight);
  EXPECT_EQ(actionFor(MovementClass::SagittalWave), RobotAction::ComeCloser);
  EXPECT_EQ(actionFor(MovementClass::ByeBye), RobotAction::StopInteraction);
  EXPECT_EQ(actionFor(MovementClass::None), RobotAction::None);
}

TEST(Behaviour, CircleTurnsOneFullTurnThenStops) {
  Behaviour b;
  const auto r = runFor(b, 12, {{3, MovementClass::Circle}});
  EXPECT_EQ(r.starts, 1);
  EXPECT_NEAR(r.angle, 2 * kPi, 0.8 * kDt * 1.01);  // within one frame's turn
  EXPECT_NEAR(r.distance, 0, 1e-12);
}

TEST(Behaviour, SideStepsReturnToTheirHeadingAndComeCloserDrivesForward) {
  BehaviourOptions o;
  Behaviour left(o), right(o), closer(o);
  const auto l = runFor(left, 10, {{0, MovementClass::WaveLeft}});
  const auto r = runFor(right, 10, {{0, MovementClass::WaveRight}});
  const auto c = runFor(closer, 10, {{0, MovementClass::SagittalWave}});
  EXPECT_NEAR(l.angle, 0, 0.06);
  EXPECT_NEAR(r.angle, 0, 0.06);
  EXPECT_NEAR(l.distance, o.stepM, o.driveSpeedMps * kDt * 1.01);
  EXPECT_NEAR(c.distance, o.closerM, o.driveSpeedMps * kDt * 1.01);
}

TEST(Behaviour, StepLeftTurnsLeftFirst) {
  Behaviour b;
  const auto out = b.update(0, MovementClass::WaveLeft, LmaFeatures{});
  EXPECT_EQ(out.action, RobotAction::StepLeft);
  EXPECT_GT(out.base.angular, 0);  // positive: counter-clockwise, to the left
}

TEST(Behaviour, PointingNodsTheHead) {
  Behaviour b;
  bool nodded = false;
  for (int i = 0; i < 30; ++i) {
    const auto out = b.update(
        i * kDt, i == 0 ? std::optional(MovementClass::Pointing) : std::nullopt, LmaFeatures{});
    if (out.headOffset && out.headOffset->tilt > 0.1) nodded = true;
  }
  EXPECT_TRUE(nodded);
}

TEST(Behaviour, CoolDownGivesOneActionPerMovement) {
  BehaviourOptions o;
  o.cooldownS = 1.0;
  Behaviour b(o);
  // ComeCloser lasts 2 s. Decisions during it and within the cool-down after
  // are ignored; one after the cool-down starts a new action.
  const auto r = runFor(b, 8,
                        {{0, MovementClass::SagittalWave},
                         {10, MovementClass::SagittalWave},     // during the action
                         {30, MovementClass::Circle},           // during the action
                         {80, MovementClass::SagittalWave},     // 0.67 s after the end
                         {100, MovementClass::SagittalWave}});  // 1.33 s after
  EXPECT_EQ(r.starts, 2);
  EXPECT_NEAR(r.distance, 2 * o.closerM, 2 * o.driveSpeedMps * kDt * 1.01);
  EXPECT_NEAR(r.angle, 0, 1e-12);
}

TEST(Behaviour, StopIsHonouredAtOnceEvenDuringAnActionAndTheCoolDown) {
  Behaviour b;
  for (int i = 0; i < 30; ++i)
    b.update(i * kDt, i == 0 ? std::optional(MovementClass::Circle) : std::nullopt, LmaFeatures{});
  const auto stop = b.update(30 * kDt, MovementClass::ByeBye, LmaFeatures{});
  EXPECT_EQ(stop.action, RobotAction::StopInteraction);
  EXPECT_TRUE(stop.stopped);
  EXPECT_EQ(stop.base.linear, 0);
  EXPECT_EQ(stop.base.angular, 0);
  EXPECT_TRUE(b.stopped());
  // Later decisions are ignored until resume(), and the base stays still.
  for (int i = 31; i < 200; ++i) {
    const auto out = b.update(
        i * kDt, i == 120 ? std::optional(MovementClass::Circle) : std::nullopt, LmaFeatures{});
    ASSERT_EQ(out.action, RobotAction::None);
    ASSERT_EQ(out.base.angular, 0);
    ASSERT_TRUE(out.stopped);
  }
  b.resume();
  const auto again = b.update(200 * kDt, MovementClass::Circle, LmaFeatures{});
  EXPECT_EQ(again.action, RobotAction::Rotate360);
  EXPECT_TRUE(again.started);
}

TEST(Behaviour, AnotherStopRightAfterAStopIsHonouredToo) {
  Behaviour b;
  EXPECT_TRUE(b.update(0, MovementClass::ByeBye, LmaFeatures{}).stopped);
  EXPECT_TRUE(b.update(kDt, MovementClass::ByeBye, LmaFeatures{}).started);
}

TEST(Behaviour, BadOptionsAreRefused) {
  BehaviourOptions o;
  o.turnSpeedRadPerS = 0;
  EXPECT_THROW(Behaviour{o}, Error);
  o = {};
  o.cooldownS = -1;
  EXPECT_THROW(Behaviour{o}, Error);
}

}  // namespace
}  // namespace horopter
