// Table III on synthetic trials; see include/horopter/interaction_eval.hpp.
#include "horopter/interaction_eval.hpp"

#include <cmath>

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

InteractionScopeResult evaluateInteraction(const InteractionEvalOptions& options,
                                           DetectionScope scope) {
  if (options.trials < 1) throw Error("eval-interaction needs at least one trial");
  if (!options.model) throw Error("eval-interaction: no movement model");
  InteractionScopeResult result;
  result.scope = scope;
  double movementMsSum = 0;
  std::int64_t movementFrames = 0;
  for (int i = 0; i < options.trials; ++i) {
    TrialOptions trial = options.trial;
    trial.seed = options.trial.seed + static_cast<std::uint64_t>(i);
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
    const TrialResult r =
        runTrackingTrial(trial, scope, std::move(extra), [&](const TrialFrame& tf) {
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
    const MovementScore score = summariseSegments(frames, options.graceFrames);
    result.movements.add(score);
    result.tracking.add(r);
    movementMsSum += r.stageMs("movement") * static_cast<double>(r.summary.completed);
    movementFrames += r.summary.completed;
    if (options.progress) options.progress(scope, i, score);
  }
  result.movementMs = movementFrames ? movementMsSum / static_cast<double>(movementFrames) : 0;
  return result;
}

}  // namespace horopter
