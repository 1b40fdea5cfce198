// The movement stage (LMA -> classifier -> behaviour) and the names of
// movements and actions; see include/horopter/movement.hpp.
#include <memory>
#include <string>

#include "horopter/behaviour.hpp"
#include "horopter/error.hpp"
#include "horopter/movement.hpp"
#include "horopter/movement_classifier.hpp"

namespace horopter {

namespace {

constexpr const char* kMovementNames[kMovementClassCount] = {
    "none", "circle", "pointing", "wave-left", "wave-right", "sagittal-wave", "bye-bye"};

class MovementStage final : public Stage {
 public:
  MovementStage(std::shared_ptr<const MovementModel> model, MovementStageOptions options)
      : options_(options), lma_(options.lma), classifier_(std::move(model)) {}

  std::string name() const override { return "movement"; }

  void process(Frame& frame) override {
    auto state = std::make_shared<MovementState>();
    const BodySample& body = frame.body;
    // A godfather elected anew after none: a new interaction.
    if (body.godfather && !hadGodfather_) {
      classifier_.reset();
      behaviour_.resume();
    }
    hadGodfather_ = body.godfather;
    state->features = lma_.update(body);
    const MovementClassifier::Step step = classifier_.update(state->features);
    state->posterior = step.posterior;
    state->likeliest = step.likeliest;
    state->decision = step.decision;
    const Behaviour::Output out = behaviour_.update(body.timeS, step.decision, state->features);
    state->action = out.action;
    state->actionStarted = out.started;
    state->interactionStopped = out.stopped;
    state->base = out.base;
    state->headOffset = out.headOffset;
    if (options_.base) options_.base->command(state->base);
    frame.movement = std::move(state);
  }

 private:
  MovementStageOptions options_;
  LmaExtractor lma_;
  MovementClassifier classifier_;
  Behaviour behaviour_;
  bool hadGodfather_ = false;
};

}  // namespace

const char* movementClassName(MovementClass movement) {
  const int i = static_cast<int>(movement);
  return i >= 0 && i < kMovementClassCount ? kMovementNames[i] : "?";
}

std::optional<MovementClass> movementClassFromName(const std::string& name) {
  for (int i = 0; i < kMovementClassCount; ++i)
    if (name == kMovementNames[i]) return static_cast<MovementClass>(i);
  return std::nullopt;
}

const char* robotActionName(RobotAction action) {
  switch (action) {
    case RobotAction::None:
      return "none";
    case RobotAction::Rotate360:
      return "rotate-360";
    case RobotAction::Acknowledge:
      return "acknowledge";
    case RobotAction::StepLeft:
      return "step-left";
    case RobotAction::StepRight:
      return "step-right";
    case RobotAction::ComeCloser:
      return "come-closer";
    case RobotAction::StopInteraction:
      return "stop-interaction";
  }
  return "?";
}

std::unique_ptr<Stage> makeMovementStage(std::shared_ptr<const MovementModel> model,
                                         MovementStageOptions options) {
  if (!model) throw Error("movement stage: no movement model");
  return std::make_unique<MovementStage>(std::move(model), options);
}

std::vector<MovementState> classifyTrack(const std::vector<BodySample>& samples,
                                         std::shared_ptr<const MovementModel> model,
                                         MovementStageOptions options) {
  auto stage = makeMovementStage(std::move(model), options);
  std::vector<MovementState> states;
  states.reserve(samples.size());
  Frame frame;
  for (const BodySample& s : samples) {
    frame.index = s.frame;
    frame.body = s;
    stage->process(frame);
    states.push_back(*frame.movement);
  }
  return states;
}

}  // namespace horopter
