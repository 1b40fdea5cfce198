// LMA features on known trajectories: angles, curvature, speed, the
// incentre's rise, the active hand, and invalid input.
#include <gtest/gtest.h>

#include <cmath>

#include "horopter/movement/lma.hpp"

namespace horopter {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kFps = 30;

PartState part(cv::Point3f p) {
  PartState s;
  s.tracked = s.observed = true;
  s.rig = p;
  s.image = {320, 240};
  return s;
}

// A body at 1.3 m with the hands hanging at rest, plus `left` and `right`
// offsets of each hand at frame i.
template <class Left, class Right>
BodySample body(int i, Left left, Right right) {
  BodySample b;
  b.frame = i;
  b.timeS = i / kFps;
  b.godfather = true;
  const cv::Point3f head(0, -0.2f, 1.3f);
  b.head = part(head);
  b.leftHand = part(head + cv::Point3f(0.22f, 0.63f, 0) + left(i));
  b.rightHand = part(head + cv::Point3f(-0.22f, 0.63f, 0) + right(i));
  return b;
}

cv::Point3f still(int) {
  return {0, 0, 0};
}

TEST(AngleSector, QuantisesIntoEightSectorsCentredOnMultiplesOf45Degrees) {
  EXPECT_EQ(angleSector(0), 0);
  EXPECT_EQ(angleSector(0.3), 0);  // 17 degrees
  EXPECT_EQ(angleSector(kPi / 4), 1);
  EXPECT_EQ(angleSector(kPi / 2), 2);
  EXPECT_EQ(angleSector(kPi), 4);
  EXPECT_EQ(angleSector(-kPi / 2), 6);
  EXPECT_EQ(angleSector(-0.3), 0);
  EXPECT_EQ(angleSector(-0.5), 7);  // -29 degrees
  EXPECT_EQ(angleSector(2 * kPi + kPi / 2), 2);
}

TEST(Lma, StraightRightHandMovementUpGivesTheUpSectorNoCurvatureAndItsSpeed) {
  LmaOptions o;
  o.smoothFrames = 1;
  LmaExtractor lma(o);
  const double speed = 0.6;  // m/s, upwards (-y)
  LmaFeatures f;
  for (int i = 0; i < 20; ++i)
    f = lma.update(body(
        i, still, [&](int k) { return cv::Point3f(0, static_cast<float>(-speed * k / kFps), 0); }));
  ASSERT_TRUE(f.valid);
  EXPECT_EQ(f.activeHand, 2);
  EXPECT_TRUE(f.rightHand.moving);
  EXPECT_FALSE(f.leftHand.moving);
  EXPECT_NEAR(f.rightHand.speed, speed, 1e-3);
  EXPECT_NEAR(f.rightHand.acceleration, 0, 1e-2);
  EXPECT_NEAR(f.rightHand.curvature, 0, 1e-3);
  EXPECT_EQ(f.rightHand.frontalSector, 2);   // up in the frontal plane
  EXPECT_EQ(f.rightHand.sagittalSector, 2);  // up in the sagittal plane
  EXPECT_EQ(f.movingParts, 4u);              // right hand only
  EXPECT_EQ(f.space, EffortSpace::Direct);
  EXPECT_EQ(f.symbols[static_cast<int>(LmaSymbol::FrontalSector)], 2);
  EXPECT_EQ(f.symbols[static_cast<int>(LmaSymbol::Curvature)], 1);  // moving, < 20 degrees
}

TEST(Lma, MovementTowardsTheRobotIsSectorZeroInTheSagittalPlane) {
  LmaOptions o;
  o.smoothFrames = 1;
  LmaExtractor lma(o);
  LmaFeatures f;
  for (int i = 0; i < 12; ++i)
    f = lma.update(body(
        i, [](int k) { return cv::Point3f(0, 0, static_cast<float>(-0.02 * k)); }, still));
  ASSERT_TRUE(f.valid);
  EXPECT_EQ(f.activeHand, 1);
  EXPECT_EQ(f.leftHand.sagittalSector, 0);    // towards the robot (-z)
  EXPECT_EQ(f.leftHand.horizontalSector, 2);  // towards the robot in the horizontal plane
  EXPECT_NEAR(f.leftHand.speed, 0.6, 1e-3);
}

TEST(Lma, CircleGivesTheCurvatureOfItsAngularStep) {
  LmaOptions o;
  o.smoothFrames = 1;
  o.stepFrames = 3;
  LmaExtractor lma(o);
  const double hz = 0.9, r = 0.17;  // the synthetic circle
  LmaFeatures f;
  for (int i = 0; i < 40; ++i)
    f = lma.update(body(i, still, [&](int k) {
      const double th = 2 * kPi * hz * k / kFps;
      return cv::Point3f(static_cast<float>(r * std::cos(th)),
                         static_cast<float>(-0.4 + r * std::sin(th)), -0.3f);
    }));
  ASSERT_TRUE(f.valid);
  // Chords over 3 frames turn by the angle swept in 3 frames.
  const double expected = 2 * kPi * hz * 3 / kFps;
  EXPECT_NEAR(f.rightHand.curvature, expected, 1e-3);
  // Speed along the chord: 2 r sin(step / 2) / dt.
  EXPECT_NEAR(f.rightHand.speed, 2 * r * std::sin(expected / 2) / (3 / kFps), 1e-3);
  // Centripetal: v^2 / r (approximately, by finite differences).
  EXPECT_NEAR(f.rightHand.acceleration, std::pow(2 * kPi * hz, 2) * r, 0.6);
  EXPECT_EQ(f.space, EffortSpace::Indirect);
}

TEST(Lma, RaisingBothHandsRaisesTheIncentreByKnownAmount) {
  LmaOptions o;
  o.smoothFrames = 1;
  LmaExtractor lma(o);
  // At rest for 10 frames, then both hands jump up by 0.3 m and stay.
  auto lift = [](int k) { return cv::Point3f(0, k < 10 ? 0.0f : -0.3f, 0); };
  LmaFeatures f;
  for (int i = 0; i < 30; ++i)
    f = lma.update(body(i, lift, lift));
  ASSERT_TRUE(f.valid);
  // Symmetric hands: the incentre lies on the midline; both hands at y+0.33
  // (relative to the head, at the same height) form an isosceles triangle
  // whose incentre moves up as the hands do. Compute the expectation directly.
  auto incentreY = [](double handDown) {
    const double a = std::hypot(0.22, handDown);  // head to each hand
    const double base = 0.44;
    // Vertices: head (y 0, weight base), two hands (y handDown, weight a each).
    return (base * 0 + 2 * a * handDown) / (base + 2 * a);
  };
  EXPECT_NEAR(f.incentreRiseM, incentreY(0.63) - incentreY(0.33), 1e-4);
  EXPECT_GT(f.incentreRiseM, 0.1);
  EXPECT_EQ(f.shape, ShapeFlow::Stable);  // the jump is over
}

TEST(Lma, TheTriangleGrowsWhileAHandMovesOutwards) {
  LmaOptions o;
  o.smoothFrames = 1;
  LmaExtractor lma(o);
  LmaFeatures f;
  for (int i = 0; i < 12; ++i)
    f = lma.update(body(
        i, [](int k) { return cv::Point3f(static_cast<float>(0.05 * k), 0, 0); }, still));
  ASSERT_TRUE(f.valid);
  EXPECT_GT(f.perimeterRate, 0.3);
  EXPECT_EQ(f.shape, ShapeFlow::Growing);
}

TEST(Lma, HandsAtRestAreStillAndNoneIsActive) {
  LmaExtractor lma;
  LmaFeatures f;
  for (int i = 0; i < 15; ++i)
    f = lma.update(body(i, still, still));
  ASSERT_TRUE(f.valid);
  EXPECT_EQ(f.activeHand, 0);
  EXPECT_EQ(f.movingParts, 0u);
  EXPECT_EQ(f.rightHand.frontalSector, -1);
  EXPECT_EQ(f.symbols[static_cast<int>(LmaSymbol::FrontalSector)], 8);
  EXPECT_NEAR(f.incentreRiseM, 0, 1e-6);
}

TEST(Lma, NoGodfatherGivesInvalidFeaturesAndStartsAgain) {
  LmaExtractor lma;
  for (int i = 0; i < 15; ++i) {
    const bool valid = lma.update(body(i, still, still)).valid;
    ASSERT_TRUE(i < 6 || valid) << i;
  }
  BodySample lost = body(15, still, still);
  lost.godfather = false;
  EXPECT_FALSE(lma.update(lost).valid);
  // The history starts again: not enough frames right after.
  EXPECT_FALSE(lma.update(body(16, still, still)).valid);
}

TEST(Lma, AnUntrackedHandKeepsItsPlaceThenRestsAndTheOtherHandGoesOn) {
  LmaOptions o;
  o.smoothFrames = 1;
  o.holdHandS = 0.3;
  LmaExtractor lma(o);
  auto raised = [](int) { return cv::Point3f(0, -0.4f, -0.2f); };  // left hand up and forward
  auto moving = [](int k) { return cv::Point3f(0, static_cast<float>(-0.02 * k), 0); };
  LmaFeatures f;
  for (int i = 0; i < 10; ++i)
    f = lma.update(body(i, raised, moving));
  ASSERT_TRUE(f.valid);
  const cv::Point3f held = f.leftHand.position;
  for (int i = 10; i < 40; ++i) {
    BodySample s = body(i, raised, moving);
    s.leftHand = PartState{};  // lost
    f = lma.update(s);
    ASSERT_TRUE(f.valid) << i;
    EXPECT_NEAR(f.rightHand.speed, 0.6, 1e-3) << i;
    if (i < 18) {
      EXPECT_NEAR(f.leftHand.position.y, held.y, 1e-5) << i;  // held
    }
  }
  // After holdHandS the lost hand hangs at rest, below the sternum.
  EXPECT_GT(f.leftHand.position.y, 0.3f);
  EXPECT_FALSE(f.leftHand.moving);
}

TEST(Lma, AHandOutOfReachIsNotTheGodfathers) {
  LmaOptions o;
  o.smoothFrames = 1;
  LmaExtractor lma(o);
  LmaFeatures f;
  for (int i = 0; i < 12; ++i) {
    BodySample s = body(i, still, still);
    if (i >= 8) s.rightHand.rig = s.head.rig + cv::Point3f(-1.5f, 0.2f, 0);  // clutter far away
    f = lma.update(s);
  }
  ASSERT_TRUE(f.valid);
  EXPECT_FALSE(f.rightHand.moving);
  EXPECT_LT(f.rightHand.position.x, -0.2f);
  EXPECT_GT(f.rightHand.position.x, -0.3f);
}

TEST(Lma, TimeGoingBackwardsStartsTheHistoryAgain) {
  LmaExtractor lma;
  for (int i = 0; i < 15; ++i)
    lma.update(body(i, still, still));
  EXPECT_FALSE(lma.update(body(3, still, still)).valid);
}

TEST(Lma, AHandWithoutDepthIsBackProjectedAtTheHeadsDepth) {
  LmaOptions o;
  o.smoothFrames = 1;
  LmaExtractor withDepth(o), withoutDepth(o);
  LmaFeatures a, b;
  for (int i = 0; i < 12; ++i) {
    BodySample s =
        body(i, still, [](int k) { return cv::Point3f(0, static_cast<float>(-0.02 * k), 0); });
    // Image positions consistent with the rig positions (the left camera).
    for (PartState* p : {&s.head, &s.leftHand, &s.rightHand})
      p->image = {static_cast<float>(o.cx + o.focalPx * (p->rig.x + 0.5 * o.baselineM) / p->rig.z),
                  static_cast<float>(o.cy + o.focalPx * p->rig.y / p->rig.z)};
    a = withDepth.update(s);
    s.rightHand.rig = cv::Point3f(NAN, NAN, NAN);
    b = withoutDepth.update(s);
  }
  ASSERT_TRUE(a.valid && b.valid);
  EXPECT_NEAR(b.rightHand.speed, a.rightHand.speed, 1e-3);
  EXPECT_EQ(b.rightHand.frontalSector, a.rightHand.frontalSector);
}

}  // namespace
}  // namespace horopter
