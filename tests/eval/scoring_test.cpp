// Per-movement scoring (Table III's definitions).
#include <gtest/gtest.h>

#include "horopter/eval/movement_scoring.hpp"

namespace horopter {
namespace {

std::vector<ScoredFrame> frames(const std::string& truth) {
  // One letter per frame: '.' none, 'c' circle, 'p' pointing.
  std::vector<ScoredFrame> out;
  for (char ch : truth)
    out.push_back({ch == 'c'   ? MovementClass::Circle
                   : ch == 'p' ? MovementClass::Pointing
                               : MovementClass::None,
                   std::nullopt, true});
  return out;
}

TEST(MovementScoring, FirstDecisionInTheWindowCountsAndLostTrackerIsAMiss) {
  auto f = frames("..cccc...pppp...cccc...");
  f[3].decision = MovementClass::Circle;  // right
  f[9].decision = MovementClass::Circle;  // wrong first, then right
  f[10].decision = MovementClass::Pointing;
  for (int i = 16; i < 20; ++i)
    f[i].onTarget = i == 16;  // lost
  f[18].decision = MovementClass::Circle;
  f[1].decision = MovementClass::ByeBye;  // spurious
  const MovementScore s = summariseSegments(f, 2);
  EXPECT_EQ(s.segments, 3);
  EXPECT_EQ(s.lost, 1);
  EXPECT_EQ(s.correct, 2);
  EXPECT_EQ(s.correctTracked, 1);
  EXPECT_EQ(s.spurious, 1);
  EXPECT_NEAR(s.trackerLossPct(), 100.0 / 3, 1e-9);
  EXPECT_NEAR(s.classificationPct(), 50.0, 1e-9);
  EXPECT_NEAR(s.realClassificationPct(), 100.0 / 3, 1e-9);
}

TEST(MovementScoring, GraceWindowStopsAtTheNextMovement) {
  auto f = frames("..cc.pp..");
  f[5].decision = MovementClass::Circle;  // inside the grace, but pointing has begun
  const auto segs = scoreSegments(f, 5);
  ASSERT_EQ(segs.size(), 2u);
  EXPECT_FALSE(segs[0].decided.has_value());
  ASSERT_TRUE(segs[1].decided.has_value());
  EXPECT_FALSE(segs[1].correct());
}

TEST(MovementScoring, ASegmentCutByTheEndIsNotScored) {
  auto f = frames("..cc..ppp");
  EXPECT_EQ(scoreSegments(f, 2).size(), 1u);
}

TEST(MovementScoring, SegmentsBeforeTheInteractionBeganAreNotScored) {
  auto f = frames("..cccc...pppp...");
  for (int i = 0; i < 5; ++i)
    f[i].interacting = false;  // circle: 3 of 4 frames outside
  const auto segs = scoreSegments(f, 2);
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_EQ(segs[0].truth, MovementClass::Pointing);
}

}  // namespace
}  // namespace horopter
