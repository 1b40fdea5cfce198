// The evaluation protocol (docs/evaluation.md): seed ranges, bootstrap
// intervals over trials, and per-trial outcomes that round-trip through JSON
// and sum to the same figures wherever they were computed.
#include <gtest/gtest.h>

#include <vector>

#include "eval/bootstrap.hpp"
#include "eval/interaction_report.hpp"
#include "eval/seed_ranges.hpp"
#include "horopter/core/error.hpp"

namespace horopter::eval {
namespace {

TEST(SeedRanges, TrialRangesAreDisjointAndStraddlingIsRefused) {
  EXPECT_EQ(trialSeedUse(0, 500000, "--seed"), SeedUse::TrialTuning);
  EXPECT_EQ(trialSeedUse(500000, 500000, "--seed"), SeedUse::TrialEvaluation);
  EXPECT_LT(seedRangeOf(SeedUse::TrialTuning).last, seedRangeOf(SeedUse::TrialEvaluation).first);
  EXPECT_LT(seedRangeOf(SeedUse::TrialEvaluation).last, seedRangeOf(SeedUse::ModelTraining).first);
  EXPECT_LT(seedRangeOf(SeedUse::ModelTraining).last, seedRangeOf(SeedUse::ModelTuning).first);
  EXPECT_THROW(trialSeedUse(499999, 2, "--seed"), Error);
  EXPECT_THROW(trialSeedUse(999999, 2, "--seed"), Error);
  EXPECT_THROW(trialSeedUse(1000000, 1, "--seed"), Error);  // the model's training data
  EXPECT_THROW(trialSeedUse(2000000, 1, "--seed"), Error);
  EXPECT_THROW(trialSeedUse(5, 0, "--trials"), Error);
}

TEST(SeedRanges, LookingInsideTrialsNeedsTuningSeeds) {
  EXPECT_NO_THROW(requireTuningSeeds(SeedUse::TrialTuning, "--diagnose"));
  try {
    requireTuningSeeds(SeedUse::TrialEvaluation, "--diagnose");
    FAIL() << "evaluation seeds were accepted for --diagnose";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--diagnose"), std::string::npos) << e.what();
  }
}

TEST(Bootstrap, IntervalHoldsTheEstimateAndIsReproducible) {
  // 40 trials, 6 movements each; trials 0-3 lost all of theirs.
  std::vector<double> lost(40, 0), movements(40, 6);
  for (int i = 0; i < 4; ++i)
    lost[static_cast<std::size_t>(i)] = 6;
  const RatioEstimate a = bootstrapRatio(lost, movements);
  const RatioEstimate b = bootstrapRatio(lost, movements);
  EXPECT_DOUBLE_EQ(a.value, 0.1);
  EXPECT_LT(a.low, a.value);
  EXPECT_GT(a.high, a.value);
  EXPECT_GT(a.low, 0.0);  // 4 of 40 trials: a resample without any is rare
  EXPECT_EQ(a.low, b.low);
  EXPECT_EQ(a.high, b.high);
  // Fewer trials, the same ratio: a wider interval.
  const std::vector<double> fewLost{6, 0, 0, 0, 0, 0, 0, 0, 0, 0}, fewMovements(10, 6);
  const RatioEstimate c = bootstrapRatio(fewLost, fewMovements);
  EXPECT_DOUBLE_EQ(c.value, 0.1);
  EXPECT_GT(c.high - c.low, a.high - a.low);
}

TEST(Bootstrap, DegenerateInputs) {
  const std::vector<double> none;
  EXPECT_EQ(bootstrapRatio(none, none).value, 0);
  const std::vector<double> zero{0, 0}, one{1, 1};
  const RatioEstimate e = bootstrapRatio(zero, one);
  EXPECT_EQ(e.low, 0);
  EXPECT_EQ(e.high, 0);
  EXPECT_EQ(bootstrapRatio(one, zero).resamples, 0);  // nothing to rate in any resample
  EXPECT_THROW(bootstrapRatio(one, std::vector<double>{1}), Error);
  EXPECT_THROW(bootstrapRatio(one, one, 1.0), Error);
}

InteractionTrial trial(std::uint64_t seed, int movements, int lost, int correct) {
  InteractionTrial t;
  t.seed = seed;
  t.movements.segments = movements;
  t.movements.lost = lost;
  t.movements.correct = t.movements.correctTracked = correct;
  t.tracking.seed = seed;
  t.tracking.frames = 300;
  t.tracking.godfatherFrames = 200;
  t.tracking.lostFrames = 50 * lost;
  t.tracking.summary.completed = 300;
  t.tracking.summary.seconds = 4.5;
  t.tracking.summary.stages = {{"capture", 300, 3.0}, {"detection", 300, 7.25}};
  return t;
}

TEST(InteractionReport, TrialsRoundTripThroughJson) {
  const InteractionTrial t = trial(12, 4, 1, 2);
  const InteractionTrial back = interactionTrialFromJson(interactionTrialJson(t));
  EXPECT_EQ(interactionTrialJson(back), interactionTrialJson(t));
  EXPECT_EQ(back.tracking.stageMs("detection"), 7.25);
  Json broken = interactionTrialJson(t);
  broken.erase("godfather_frames");
  EXPECT_THROW(interactionTrialFromJson(broken), Error);
  broken = interactionTrialJson(t);
  broken["lost"] = "many";
  EXPECT_THROW(interactionTrialFromJson(broken), Error);
  broken = interactionTrialJson(t);
  broken["lost"] = 9;  // more than its 4 movements
  EXPECT_THROW(interactionTrialFromJson(broken), Error);
}

TEST(InteractionReport, ScopeCountsWholeTrialLossesAndWorstFirst) {
  const InteractionScopeResult r = summariseInteraction(
      DetectionScope::HoropterRegion,
      {trial(1, 6, 0, 6), trial(2, 4, 4, 0), trial(3, 6, 1, 4), trial(4, 0, 0, 0)});
  EXPECT_EQ(r.trialsLostAll(), 1);  // seed 2; seed 4 had no movement to lose
  const auto worst = worstInteractionTrials(r, 2);
  ASSERT_EQ(worst.size(), 2u);
  EXPECT_EQ(worst[0]->seed, 2u);
  EXPECT_EQ(worst[1]->seed, 3u);
  const Json j = interactionScopeJson(r);
  EXPECT_EQ(j["movements"], 16);
  EXPECT_EQ(j["lost"], 5);
  EXPECT_DOUBLE_EQ(j["tracker_loss"].get<double>(), 100.0 * 5 / 16);
  EXPECT_EQ(j["trials_lost_all"], 1);
  EXPECT_EQ(j["per_trial"].size(), 4u);
  EXPECT_LE(j["tracker_loss_ci95"][0].get<double>(), j["tracker_loss"].get<double>());
  EXPECT_GE(j["tracker_loss_ci95"][1].get<double>(), j["tracker_loss"].get<double>());
  // Summing the JSON outcomes again gives the same report.
  std::vector<InteractionTrial> again;
  for (const Json& t : j["per_trial"])
    again.push_back(interactionTrialFromJson(t));
  EXPECT_EQ(interactionScopeJson(summariseInteraction(DetectionScope::HoropterRegion, again)), j);
}

}  // namespace
}  // namespace horopter::eval
