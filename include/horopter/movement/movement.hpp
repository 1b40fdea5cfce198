// Movement analysis as a pipeline stage: what it puts in Frame::movement
// (the LMA features, the posterior over the movements, the decision and the
// robot's answer), the stage that fills it and the overlay that shows it.
//
// The chain per frame: BodySample (tracking) -> LmaExtractor (lma.hpp) ->
// MovementClassifier (movement_classifier.hpp) -> Behaviour (behaviour.hpp).
#pragma once

#include "horopter/core/export.hpp"

#include <array>
#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "horopter/hardware/base.hpp"
#include "horopter/hardware/head.hpp"
#include "horopter/interaction/body.hpp"
#include "horopter/movement/lma.hpp"

namespace horopter {

// The six movements of the paper's Table II and "none", in the order of
// synth::Movement (so a synthetic label converts by value).
enum class MovementClass { None, Circle, Pointing, WaveLeft, WaveRight, SagittalWave, ByeBye };
inline constexpr int kMovementClassCount = 7;
// "none", "circle", "pointing", "wave-left", "wave-right", "sagittal-wave", "bye-bye".
HOROPTER_API const char* movementClassName(MovementClass movement);
// The inverse of movementClassName; std::nullopt for an unknown name.
HOROPTER_API std::optional<MovementClass> movementClassFromName(const std::string& name);

using MovementPosterior = std::array<double, kMovementClassCount>;

// The robot's answers (Table II).
enum class RobotAction {
  None,
  Rotate360,        // circle
  Acknowledge,      // pointing: nod, then turn towards the pointed direction
  StepLeft,         // wave left: a side step to the robot's own left
  StepRight,        // wave right: a side step to the robot's own right
  ComeCloser,       // sagittal wave: drive towards the person
  StopInteraction,  // bye-bye: stop at once; later decisions are ignored
};
HOROPTER_API const char* robotActionName(RobotAction action);

// What the movement stage knows after a frame.
struct HOROPTER_API MovementState {
  LmaFeatures features;
  MovementPosterior posterior{};                  // sums to 1
  MovementClass likeliest = MovementClass::None;  // argmax of the posterior
  // Set on the frame where the posterior of a movement passed the threshold
  // (once per movement: it re-arms when that posterior falls again).
  std::optional<MovementClass> decision;
  RobotAction action = RobotAction::None;  // the action running now (None when idle)
  bool actionStarted = false;              // `action` started on this frame
  bool interactionStopped = false;         // a bye-bye was honoured
  // The commands for this frame: a base velocity every frame (the base's
  // watchdog wants one at least every 200 ms) and, during a gesture, head
  // angles relative to where tracking points the head (added to its command).
  hw::BaseVelocity base;
  std::optional<hw::HeadAngles> headOffset;
};

class MovementModel;  // movement_classifier.hpp

struct HOROPTER_API MovementStageOptions {
  LmaOptions lma;
  // Optional: the stage sends each frame's base velocity here (not owned;
  // must outlive the pipeline). Head offsets are left to the head control.
  hw::Base* base = nullptr;
};

// LMA features, classification and behaviour, one body sample at a time (in
// order): the work of the pipeline's stage "movement" (makeMovementStage).
class HOROPTER_API MovementAnalyser {
 public:
  // Throws horopter::Error without a model.
  explicit MovementAnalyser(std::shared_ptr<const MovementModel> model,
                            MovementStageOptions options = {});
  ~MovementAnalyser();
  MovementAnalyser(MovementAnalyser&&) noexcept;
  MovementState update(const BodySample& body);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The analyser over a recorded track, sample by sample (no pipeline).
HOROPTER_API std::vector<MovementState> classifyTrack(const std::vector<BodySample>& samples,
                                                      std::shared_ptr<const MovementModel> model,
                                                      MovementStageOptions options = {});

// Draws the likeliest movement, the posterior as bars, the last decision and
// the running action into the top right of a BGR image (CV_8UC3).
HOROPTER_API void drawMovementOverlay(cv::Mat& bgr, const MovementState& state);

}  // namespace horopter
