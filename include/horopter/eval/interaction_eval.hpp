// The paper's Table III on synthetic trials: the whole pipeline (tracking
// trials of horopter/eval/tracking_eval.hpp with the movement stage appended),
// scored per movement performed (horopter/eval/movement_scoring.hpp), once with
// detection over the full image and once inside the horopter's region.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "horopter/eval/movement_scoring.hpp"
#include "horopter/eval/tracking_eval.hpp"
#include "horopter/movement/movement.hpp"
#include "horopter/movement/movement_classifier.hpp"

namespace horopter {

struct InteractionEvalOptions {
  TrialOptions trial;  // seed = the first trial's; trial i uses seed + i
  int trials = 20;
  int graceFrames = 15;  // a decision this many frames after a movement still counts
  std::shared_ptr<const MovementModel> model;
  // When set: each trial's tracked body and the truth are written to
  // DIR/<scope>_<seed>.csv (a body track file with the truth column).
  std::string writeTracksDir;
  // When set, each trial keeps why its parts were lost (LossDiagnosis) and
  // its election's timeline (InteractionTrial::diagnosis): tuning seeds only.
  bool diagnose = false;
  // Trials run this many at a time (1..64). Results do not depend on it, but
  // frames/s are then measured with the trials competing for the cores.
  int jobs = 1;
  // Called after each trial with (scope, trial index, the trial's score); one
  // call at a time, in order of completion.
  std::function<void(DetectionScope, int, const MovementScore&)> progress;
};

// Why a trial lost what it lost (InteractionEvalOptions::diagnose).
struct TrialDiagnosis {
  LossDiagnosis causes;                   // lost parts by cause, frames
  std::int64_t truthElectedFrame = -1;    // the first frame with a godfather by the truth
  std::int64_t trackerElectedFrame = -1;  // ... and by the tracker (-1: never)
  int releases = 0;  // the tracker's godfather released while the truth still had one
};

// The first cause of a trial's losses that holds, in this order:
// "never-elected", "released" (the godfather lost and released), "elected-late"
// (over 1 s after the truth), then the part and cause with the most lost
// frames ("right-hand:right-view-out", ...); "" when nothing was lost.
std::string trialFailureCause(const TrialDiagnosis& diagnosis, double framesPerSecond);

// One trial's outcome: what the scope's figures are summed from.
struct InteractionTrial {
  std::uint64_t seed = 0;
  MovementScore movements;   // this trial's movements
  TrialResult tracking;      // its per-frame tracking scores and stage times (no trace)
  TrialDiagnosis diagnosis;  // filled with InteractionEvalOptions::diagnose
  // Every scored movement of the trial was lost: the person was lost for the
  // whole session, whatever the mean over trials says.
  bool lostAll() const { return movements.segments > 0 && movements.lost == movements.segments; }
};

struct InteractionScopeResult {
  DetectionScope scope = DetectionScope::HoropterRegion;
  std::vector<InteractionTrial> trials;  // in seed order
  MovementScore movements;  // per-movement: tracker loss, classification, real classification
  ScopeScore tracking;      // per-frame tracking scores and stage times
  double movementMs = 0;    // the movement stage, mean ms per frame
  int trialsLostAll() const;
  // Frames per second of the pipeline without the synthetic renderer: 1000 /
  // the sum of every stage's mean ms but capture's (one frame through every
  // stage on one core at a time; the lanes overlap, so a run is faster).
  double visionFps() const;
};

// Runs `trials` trials in `scope`. Throws horopter::Error for bad options.
InteractionScopeResult evaluateInteraction(const InteractionEvalOptions& options,
                                           DetectionScope scope);

// Runs trial `index` (seed options.trial.seed + index) alone: what a worker
// of a distributed evaluation does.
InteractionTrial runInteractionTrial(const InteractionEvalOptions& options, DetectionScope scope,
                                     int index);

// Sums trials (in the order given) into a scope's result: evaluateInteraction
// is runInteractionTrial over every index, then this.
InteractionScopeResult summariseInteraction(DetectionScope scope,
                                            std::vector<InteractionTrial> trials);

}  // namespace horopter
