// The godfather election with a fake clock: the frame times are given.
#include <gtest/gtest.h>

#include "horopter/core/error.hpp"
#include "horopter/interaction/godfather.hpp"

namespace horopter {
namespace {

constexpr double kDt = 1.0 / 30;

// Feeds `frames` frames of the same observation from time `t`, returns the time after.
double feed(GodfatherElection& e, double t, int frames, std::optional<bool> seen) {
  for (int i = 0; i < frames; ++i, t += kDt)
    e.update(t, seen);
  return t;
}

TEST(GodfatherElection, ElectedAfterTSecondsInsideNotBefore) {
  GodfatherElection e(ElectionOptions{2.0, 1.0, 0.3});
  EXPECT_EQ(e.update(0.0, true), ElectionState::Candidate);
  EXPECT_EQ(e.update(1.99, true), ElectionState::Candidate);
  EXPECT_NEAR(e.candidateS(1.99), 1.99, 1e-12);
  EXPECT_EQ(e.update(2.0, true), ElectionState::Godfather);
}

TEST(GodfatherElection, SubjectsOutsideTheZoneNeverStartACandidacy) {
  GodfatherElection e;
  feed(e, 0, 300, false);  // ten seconds seen outside
  EXPECT_EQ(e.state(), ElectionState::None);
  feed(e, 10, 300, std::nullopt);
  EXPECT_EQ(e.state(), ElectionState::None);
}

TEST(GodfatherElection, ShortMissesKeepTheCandidacyLongOnesEndIt) {
  GodfatherElection e(ElectionOptions{2.0, 1.0, 0.3});
  double t = feed(e, 0, 30, true);  // 1 s inside
  t = feed(e, t, 6, std::nullopt);  // 0.2 s missed: within the grace
  EXPECT_EQ(e.state(), ElectionState::Candidate);
  t = feed(e, t, 25, true);  // 2.03 s since the start
  EXPECT_EQ(e.state(), ElectionState::Godfather);

  GodfatherElection f(ElectionOptions{2.0, 1.0, 0.3});
  t = feed(f, 0, 30, true);
  t = feed(f, t, 12, std::nullopt);  // 0.4 s missed: the candidacy ends
  EXPECT_EQ(f.state(), ElectionState::None);
  t = feed(f, t, 45, true);  // 1.5 s: a new candidacy, not yet elected
  EXPECT_EQ(f.state(), ElectionState::Candidate);
  EXPECT_NEAR(f.candidateS(t - kDt), 44 * kDt, 1e-9);
}

TEST(GodfatherElection, ReleasedAfterTLostOutsideAndKeptWhileBackInTime) {
  GodfatherElection e(ElectionOptions{2.0, 1.0, 0.3});
  double t = feed(e, 0, 61, true);
  ASSERT_EQ(e.state(), ElectionState::Godfather);
  t = feed(e, t, 20, false);  // 0.67 s outside
  EXPECT_EQ(e.state(), ElectionState::Godfather);
  const double lastInside = t;
  t = feed(e, t, 1, true);  // back inside: the clock restarts
  feed(e, t, 25, std::nullopt);
  EXPECT_EQ(e.state(), ElectionState::Godfather);
  EXPECT_EQ(e.update(lastInside + 0.99, false), ElectionState::Godfather);
  // T_lost after the last sighting inside: released.
  EXPECT_EQ(e.update(lastInside + 1.0, false), ElectionState::None);
}

TEST(GodfatherElection, ZeroElectionTimeElectsOnTheFirstSighting) {
  GodfatherElection e(ElectionOptions{0.0, 1.0, 0.3});
  EXPECT_EQ(e.update(5.0, true), ElectionState::Godfather);
}

TEST(GodfatherElection, NegativeTimesAreAnError) {
  EXPECT_THROW(GodfatherElection(ElectionOptions{-1, 1, 0.3}), Error);
  EXPECT_THROW(GodfatherElection(ElectionOptions{2, -1, 0.3}), Error);
}

}  // namespace
}  // namespace horopter
