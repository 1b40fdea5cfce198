// Table III on synthetic trials; see include/horopter/interaction_eval.hpp.
#include "horopter/interaction_eval.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "horopter/body_track_file.hpp"
#include "horopter/error.hpp"

namespace horopter {

namespace {
// The synthetic scene's default: a 60 degree horizontal field of view.
constexpr double kHalfFieldOfViewRad = 30.0 * 3.14159265358979323846 / 180.0;
}  // namespace

double InteractionScopeResult::visionFps() const {
  return tracking.visionMs > 0 ? 1000.0 / tracking.visionMs : 0;
}

namespace {

struct TrialOutcome {
  MovementScore score;
  TrialResult tracking;
};

TrialOutcome runTrial(const InteractionEvalOptions& options, DetectionScope scope, int index) {
  TrialOptions trial = options.trial;
  trial.seed = options.trial.seed + static_cast<std::uint64_t>(index);
  // The LMA back-projects parts without depth with the scene's camera.
  const synth::SceneOptions scene = trialScene(trial);
  MovementStageOptions stage;
  stage.lma.focalPx =
      scene.focalPx > 0 ? scene.focalPx : 0.5 * scene.width / std::tan(kHalfFieldOfViewRad);
  stage.lma.cx = 0.5 * (scene.width - 1);
  stage.lma.cy = 0.5 * (scene.height - 1);
  stage.lma.baselineM = scene.baselineM;
  std::vector<std::unique_ptr<Stage>> extra;
  extra.push_back(makeMovementStage(options.model, stage));
  std::vector<ScoredFrame> frames;
  std::vector<BodySample> bodies;
  std::vector<MovementClass> truths;
  TrialOutcome outcome;
  outcome.tracking = runTrackingTrial(trial, scope, std::move(extra), [&](const TrialFrame& tf) {
    ScoredFrame s;
    s.truth = static_cast<MovementClass>(static_cast<int>(tf.truth.people.at(0).movement));
    if (tf.frame.movement) s.decision = tf.frame.movement->decision;
    s.onTarget = tf.frame.body.godfather && !tf.lost;
    s.interacting = tf.truthGodfather;
    frames.push_back(s);
    if (!options.writeTracksDir.empty()) {
      bodies.push_back(tf.frame.body);
      truths.push_back(s.truth);
    }
  });
  if (!options.writeTracksDir.empty())
    writeBodyTrack(options.writeTracksDir + "/" +
                       (scope == DetectionScope::FullImage ? "full_" : "region_") +
                       std::to_string(trial.seed) + ".csv",
                   bodies, truths);
  outcome.score = summariseSegments(frames, options.graceFrames);
  return outcome;
}

}  // namespace

InteractionScopeResult evaluateInteraction(const InteractionEvalOptions& options,
                                           DetectionScope scope) {
  if (options.trials < 1) throw Error("eval-interaction needs at least one trial");
  if (!options.model) throw Error("eval-interaction: no movement model");
  if (options.jobs < 1 || options.jobs > 64) throw Error("eval-interaction: jobs must be 1..64");

  // Trials are independent: `jobs` workers take the next index until none is
  // left; the results are summed in trial order, so they do not depend on jobs.
  std::vector<TrialOutcome> outcomes(static_cast<std::size_t>(options.trials));
  std::atomic<int> next{0};
  std::mutex progressMutex;
  std::exception_ptr failure;
  const auto work = [&] {
    for (int i = next++; i < options.trials; i = next++) {
      try {
        outcomes[static_cast<std::size_t>(i)] = runTrial(options, scope, i);
      } catch (...) {
        const std::lock_guard lock(progressMutex);
        if (!failure) failure = std::current_exception();
        next = options.trials;  // the others stop after their trial
        return;
      }
      if (options.progress) {
        const std::lock_guard lock(progressMutex);
        options.progress(scope, i, outcomes[static_cast<std::size_t>(i)].score);
      }
    }
  };
  std::vector<std::thread> workers;
  for (int j = 1; j < std::min(options.jobs, options.trials); ++j)
    workers.emplace_back(work);
  work();
  for (std::thread& w : workers)
    w.join();
  if (failure) std::rethrow_exception(failure);

  InteractionScopeResult result;
  result.scope = scope;
  double movementMsSum = 0;
  std::int64_t movementFrames = 0;
  for (const TrialOutcome& o : outcomes) {
    result.movements.add(o.score);
    result.tracking.add(o.tracking);
    movementMsSum +=
        o.tracking.stageMs("movement") * static_cast<double>(o.tracking.summary.completed);
    movementFrames += o.tracking.summary.completed;
  }
  result.movementMs = movementFrames ? movementMsSum / static_cast<double>(movementFrames) : 0;
  return result;
}

}  // namespace horopter
