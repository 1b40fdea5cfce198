// Labelled training sequences from the synthetic scene's movement generator
// (engine/synthetic/people.hpp), without rendering: the main person's head
// and hands at each frame, projected into the left image, with tracking-like
// noise, and the movement label. Training the default model takes seconds.
//
// Seed ranges, kept apart so no evaluation runs on data the model saw:
//   training   kTrainingSeedBase .. + sequences - 1    (1 000 000 ..)
//   tuning     kTuningSeedBase ..                      (2 000 000 ..; the parameters
//                                                       in MovementModelParams were
//                                                       chosen on these)
//   evaluation below 1 000 000 (eval-interaction's default --seed is 1)
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "horopter/interaction/body.hpp"
#include "horopter/movement/lma.hpp"
#include "horopter/movement/movement.hpp"
#include "horopter/movement/movement_classifier.hpp"

namespace horopter {

inline constexpr std::uint64_t kTrainingSeedBase = 1000000;
inline constexpr std::uint64_t kTuningSeedBase = 2000000;
inline constexpr std::uint64_t kEvaluationSeedLimit = 1000000;

struct SequenceOptions {
  double framesPerSecond = 30;
  double seconds = 0;  // 0: the walk in and the six movements once, plus a rest
  // Per sequence, uniformly drawn: a wider spread than the scene's own.
  double speedMin = 0.75, speedMax = 1.35;
  double amplitudeMin = 0.7, amplitudeMax = 1.3;
  double maxHeadPanRad = 0.12, maxHeadTiltRad = 0.1;  // the rig not quite centred
  // Per frame: Gaussian position noise, missing depth, coasting (no update).
  double pixelNoise = 1.5;
  double lateralNoiseM = 0.01, depthNoiseM = 0.025;
  double missingDepthRate = 0.05;
  double coastRate = 0.03;  // a part keeps last frame's position
  // A hand's track is lost (tracked = false) from a frame with this
  // probability, for 3 to 20 frames.
  double handLossRate = 0.01;
  // A hand's track jumps to something else within reach (clutter, the other
  // hand) from a frame with this probability, for 1 to 6 frames.
  double handOutlierRate = 0.01;
};

struct LabelledSequence {
  std::uint64_t seed = 0;
  std::vector<BodySample> samples;
  std::vector<MovementClass> labels;  // the truth, one per sample
};

// Deterministic for (seed, options).
LabelledSequence syntheticSequence(std::uint64_t seed, const SequenceOptions& options = {});

struct TrainingOptions {
  std::uint64_t firstSeed = kTrainingSeedBase;
  int sequences = 300;
  SequenceOptions sequence;
  LmaOptions lma;
  MovementModelParams params;
  // Called after each sequence with (done, total).
  std::function<void(int, int)> progress;
};

// Counts the LMA symbols of `options.sequences` sequences from firstSeed on.
MovementModel trainMovementModel(const TrainingOptions& options);

// The model the commands use without --model: trainMovementModel with the
// defaults (deterministic; a few seconds).
std::shared_ptr<const MovementModel> defaultMovementModel();

// The model in `path`, or the default model when `path` is empty.
std::shared_ptr<const MovementModel> loadOrTrainMovementModel(const std::string& path);

// Frame-level accuracy of a model on sequences (for tuning and tests): the
// fraction of frames with valid features whose likeliest class is the label.
double frameAccuracy(const MovementModel& model, const std::vector<LabelledSequence>& sequences,
                     const LmaOptions& lma = {});

}  // namespace horopter
