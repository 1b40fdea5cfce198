// The paper's Table III on synthetic trials: the whole pipeline (tracking
// trials of horopter/tracking_eval.hpp with the movement stage appended),
// scored per movement performed (horopter/movement_scoring.hpp), once with
// detection over the full image and once inside the horopter's region.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "horopter/movement.hpp"
#include "horopter/movement_classifier.hpp"
#include "horopter/movement_scoring.hpp"
#include "horopter/tracking_eval.hpp"

namespace horopter {

struct InteractionEvalOptions {
  TrialOptions trial;  // seed = the first trial's; trial i uses seed + i
  int trials = 20;
  int graceFrames = 15;  // a decision this many frames after a movement still counts
  std::shared_ptr<const MovementModel> model;
  // When set: each trial's tracked body and the truth are written to
  // DIR/<scope>_<seed>.csv (a body track file with the truth column).
  std::string writeTracksDir;
  // Trials run this many at a time (1..64). Results do not depend on it, but
  // frames/s are then measured with the trials competing for the cores.
  int jobs = 1;
  // Called after each trial with (scope, trial index, the trial's score); one
  // call at a time, in order of completion.
  std::function<void(DetectionScope, int, const MovementScore&)> progress;
};

struct InteractionScopeResult {
  DetectionScope scope = DetectionScope::HoropterRegion;
  MovementScore movements;  // per-movement: tracker loss, classification, real classification
  ScopeScore tracking;      // per-frame tracking scores and stage times
  double movementMs = 0;    // the movement stage, mean ms per frame
  // Frames per second of the pipeline without the synthetic renderer: 1000 /
  // the sum of every stage's mean ms but capture's (one frame through every
  // stage on one core at a time; the lanes overlap, so a run is faster).
  double visionFps() const;
};

// Runs `trials` trials in `scope`. Throws horopter::Error for bad options.
InteractionScopeResult evaluateInteraction(const InteractionEvalOptions& options,
                                           DetectionScope scope);

}  // namespace horopter
