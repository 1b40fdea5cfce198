// The movement analyser (LMA -> classifier -> behaviour) and the names of
// movements and actions; see include/horopter/movement/movement.hpp.
#include <memory>
#include <string>

#include "horopter/core/error.hpp"
#include "horopter/movement/behaviour.hpp"
#include "horopter/movement/movement.hpp"
#include "horopter/movement/movement_classifier.hpp"

namespace horopter {

namespace {

constexpr const char* kMovementNames[kMovementClassCount] = {
    "none", "circle", "pointing", "wave-left", "wave-right", "sagittal-wave", "bye-bye"};

}  // namespace

struct MovementAnalyser::Impl {
  Impl(std::shared_ptr<const MovementModel> model, MovementStageOptions o)
      : options(o), lma(o.lma), classifier(std::move(model)) {}
  MovementStageOptions options;
  LmaExtractor lma;
  MovementClassifier classifier;
  Behaviour behaviour;
  bool hadGodfather = false;
};

MovementAnalyser::MovementAnalyser(std::shared_ptr<const MovementModel> model,
                                   MovementStageOptions options) {
  if (!model) throw Error("movement stage: no movement model");
  impl_ = std::make_unique<Impl>(std::move(model), options);
}

MovementAnalyser::~MovementAnalyser() = default;
MovementAnalyser::MovementAnalyser(MovementAnalyser&&) noexcept = default;

MovementState MovementAnalyser::update(const BodySample& body) {
  Impl& m = *impl_;
  MovementState state;
  // A godfather elected anew after none: a new interaction.
  if (body.godfather && !m.hadGodfather) {
    m.classifier.reset();
    m.behaviour.resume();
  }
  m.hadGodfather = body.godfather;
  state.features = m.lma.update(body);
  const MovementClassifier::Step step = m.classifier.update(state.features);
  state.posterior = step.posterior;
  state.likeliest = step.likeliest;
  state.decision = step.decision;
  const Behaviour::Output out = m.behaviour.update(body.timeS, step.decision, state.features);
  state.action = out.action;
  state.actionStarted = out.started;
  state.interactionStopped = out.stopped;
  state.base = out.base;
  state.headOffset = out.headOffset;
  if (m.options.base) m.options.base->command(state.base);
  return state;
}

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

std::vector<MovementState> classifyTrack(const std::vector<BodySample>& samples,
                                         std::shared_ptr<const MovementModel> model,
                                         MovementStageOptions options) {
  MovementAnalyser analyser(std::move(model), options);
  std::vector<MovementState> states;
  states.reserve(samples.size());
  for (const BodySample& s : samples)
    states.push_back(analyser.update(s));
  return states;
}

}  // namespace horopter
