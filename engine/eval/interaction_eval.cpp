// Table III on synthetic trials; see include/horopter/eval/interaction_eval.hpp.
#include "horopter/eval/interaction_eval.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "eval/parallel_trials.hpp"
#include "horopter/app/interaction_stages.hpp"
#include "horopter/core/error.hpp"
#include "horopter/movement/body_track_file.hpp"

namespace horopter {

namespace {
// The synthetic scene's default: a 60 degree horizontal field of view.
constexpr double kHalfFieldOfViewRad = 30.0 * 3.14159265358979323846 / 180.0;
}  // namespace

double InteractionScopeResult::visionFps() const {
  return tracking.visionMs > 0 ? 1000.0 / tracking.visionMs : 0;
}

int InteractionScopeResult::trialsLostAll() const {
  return static_cast<int>(
      std::count_if(trials.begin(), trials.end(), [](const auto& t) { return t.lostAll(); }));
}

std::string trialFailureCause(const TrialDiagnosis& d, double framesPerSecond) {
  if (d.truthElectedFrame < 0) return "";
  if (d.trackerElectedFrame < 0) return "never-elected";
  if (d.releases > 0) return "released";
  if (static_cast<double>(d.trackerElectedFrame - d.truthElectedFrame) > framesPerSecond)
    return "elected-late";
  static const char* const kParts[3] = {"head", "left-hand", "right-hand"};
  std::int64_t most = 0;
  std::string cause;
  for (int part = 0; part < 3; ++part)
    for (int c = 0; c < static_cast<int>(LossCause::Count); ++c)
      if (d.causes.counts[part][c] > most) {
        most = d.causes.counts[part][c];
        cause = std::string(kParts[part]) + ":" + lossCauseName(static_cast<LossCause>(c));
      }
  return cause;
}

InteractionTrial runInteractionTrial(const InteractionEvalOptions& options, DetectionScope scope,
                                     int index) {
  if (!options.model) throw Error("eval-interaction: no movement model");
  if (index < 0) throw Error("eval-interaction: a trial index is >= 0");
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
  InteractionTrial outcome;
  outcome.seed = trial.seed;
  bool wasElected = false;
  outcome.tracking = runTrackingTrial(trial, scope, std::move(extra), [&](const TrialFrame& tf) {
    ScoredFrame s;
    s.truth = static_cast<MovementClass>(static_cast<int>(tf.truth.people.at(0).movement));
    if (tf.frame.movement) s.decision = tf.frame.movement->decision;
    s.onTarget = tf.frame.body.godfather && !tf.lost;
    s.interacting = tf.truthGodfather;
    frames.push_back(s);
    if (options.diagnose) {
      TrialDiagnosis& d = outcome.diagnosis;
      d.causes.add(tf, trial);
      const bool elected =
          tf.frame.tracking && tf.frame.tracking->election == ElectionState::Godfather;
      if (tf.truthGodfather && d.truthElectedFrame < 0) d.truthElectedFrame = tf.frame.index;
      if (elected && d.trackerElectedFrame < 0) d.trackerElectedFrame = tf.frame.index;
      if (!elected && wasElected && tf.truthGodfather) ++d.releases;
      wasElected = elected;
    }
    if (!options.writeTracksDir.empty()) {
      bodies.push_back(tf.frame.body);
      truths.push_back(s.truth);
    }
  });
  outcome.tracking.summary.trace.clear();  // a trial's outcome is kept; its trace is not needed
  if (!options.writeTracksDir.empty())
    writeBodyTrack(options.writeTracksDir + "/" +
                       (scope == DetectionScope::FullImage ? "full_" : "region_") +
                       std::to_string(trial.seed) + ".csv",
                   bodies, truths);
  outcome.movements = summariseSegments(frames, options.graceFrames);
  return outcome;
}

InteractionScopeResult evaluateInteraction(const InteractionEvalOptions& options,
                                           DetectionScope scope) {
  if (options.trials < 1) throw Error("eval-interaction needs at least one trial");
  if (!options.model) throw Error("eval-interaction: no movement model");
  if (options.jobs < 1 || options.jobs > 64) throw Error("eval-interaction: jobs must be 1..64");
  std::function<void(int, const InteractionTrial&)> done;
  if (options.progress)
    done = [&](int i, const InteractionTrial& t) { options.progress(scope, i, t.movements); };
  return summariseInteraction(
      scope, eval::runTrials<InteractionTrial>(
                 options.trials, options.jobs,
                 [&](int i) { return runInteractionTrial(options, scope, i); }, done));
}

InteractionScopeResult summariseInteraction(DetectionScope scope,
                                            std::vector<InteractionTrial> trials) {
  InteractionScopeResult result;
  result.scope = scope;
  double movementMsSum = 0;
  std::int64_t movementFrames = 0;
  for (const InteractionTrial& o : trials) {
    result.movements.add(o.movements);
    result.tracking.add(o.tracking);
    movementMsSum +=
        o.tracking.stageMs("movement") * static_cast<double>(o.tracking.summary.completed);
    movementFrames += o.tracking.summary.completed;
  }
  result.tracking.scope = scope;
  result.movementMs = movementFrames ? movementMsSum / static_cast<double>(movementFrames) : 0;
  result.trials = std::move(trials);
  return result;
}

}  // namespace horopter
