// evaluateInteraction: trials run in parallel (jobs) give the same counts as
// one at a time, and bad options are clear errors.
#include <gtest/gtest.h>

#include "horopter/core/error.hpp"
#include "horopter/eval/interaction_eval.hpp"
#include "horopter/eval/movement_training.hpp"

namespace horopter {
namespace {

InteractionEvalOptions smallRun(int jobs) {
  InteractionEvalOptions o;
  TrainingOptions training;
  training.sequences = 20;
  o.model = std::make_shared<const MovementModel>(trainMovementModel(training));
  o.trials = 3;
  o.trial.seed = 11;
  o.trial.frames = 100;  // past the election (2 s at 30 frames/s)
  o.trial.width = 160;
  o.trial.height = 120;
  o.jobs = jobs;
  return o;
}

TEST(InteractionEval, ParallelTrialsGiveTheSameCounts) {
  int progressCalls = 0;
  InteractionEvalOptions serial = smallRun(1);
  InteractionEvalOptions parallel = smallRun(2);
  parallel.progress = [&](DetectionScope, int, const MovementScore&) { ++progressCalls; };
  const InteractionScopeResult a = evaluateInteraction(serial, DetectionScope::HoropterRegion);
  const InteractionScopeResult b = evaluateInteraction(parallel, DetectionScope::HoropterRegion);
  EXPECT_EQ(progressCalls, 3);
  EXPECT_EQ(a.tracking.trials, 3);
  EXPECT_EQ(b.tracking.trials, 3);
  EXPECT_EQ(a.tracking.frames, 3 * 100);
  EXPECT_EQ(b.tracking.frames, a.tracking.frames);
  EXPECT_EQ(b.tracking.godfatherFrames, a.tracking.godfatherFrames);
  EXPECT_EQ(b.tracking.lostFrames, a.tracking.lostFrames);
  // Something to compare: faces were found and a godfather elected.
  EXPECT_GT(a.tracking.detections, 0);
  EXPECT_GT(a.tracking.godfatherFrames, 0);
  EXPECT_EQ(b.tracking.detections, a.tracking.detections);
  EXPECT_EQ(b.tracking.falseDetections, a.tracking.falseDetections);
  EXPECT_EQ(b.movements.segments, a.movements.segments);
  EXPECT_EQ(b.movements.lost, a.movements.lost);
  EXPECT_EQ(b.movements.correctTracked, a.movements.correctTracked);
  EXPECT_EQ(b.movements.spurious, a.movements.spurious);
}

TEST(InteractionEval, BadJobsIsAClearError) {
  InteractionEvalOptions o = smallRun(0);
  try {
    evaluateInteraction(o, DetectionScope::HoropterRegion);
    FAIL() << "jobs = 0 was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("jobs"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace horopter
