// Table II as velocity profiles; see include/horopter/movement/behaviour.hpp.
#include "horopter/movement/behaviour.hpp"

#include <cmath>
#include <string>

#include "horopter/core/error.hpp"

namespace horopter {

namespace {
constexpr double kPi = 3.14159265358979323846;
}

RobotAction actionFor(MovementClass movement) {
  switch (movement) {
    case MovementClass::Circle:
      return RobotAction::Rotate360;
    case MovementClass::Pointing:
      return RobotAction::Acknowledge;
    case MovementClass::WaveLeft:
      return RobotAction::StepLeft;
    case MovementClass::WaveRight:
      return RobotAction::StepRight;
    case MovementClass::SagittalWave:
      return RobotAction::ComeCloser;
    case MovementClass::ByeBye:
      return RobotAction::StopInteraction;
    case MovementClass::None:
      break;
  }
  return RobotAction::None;
}

Behaviour::Behaviour(BehaviourOptions options) : options_(options) {
  auto positive = [](double v, const char* name) {
    if (!(v > 0 && std::isfinite(v)))
      throw Error(std::string("behaviour: ") + name + " must be positive, got " +
                  std::to_string(v));
  };
  positive(options_.turnSpeedRadPerS, "turn speed");
  positive(options_.driveSpeedMps, "drive speed");
  positive(options_.stepM, "step length");
  positive(options_.closerM, "come-closer distance");
  positive(options_.nodS, "nod duration");
  positive(options_.pointedTargetM, "pointed target distance");
  if (!(options_.cooldownS >= 0)) throw Error("behaviour: cool-down must be >= 0 s");
}

void Behaviour::resume() {
  stopped_ = false;
}

void Behaviour::start(RobotAction action, double timeS, const LmaFeatures& features) {
  const double w = options_.turnSpeedRadPerS, v = options_.driveSpeedMps;
  auto turn = [&](double angle) {
    return Phase{std::abs(angle) / w, {0, angle >= 0 ? w : -w}, false};
  };
  phases_.clear();
  switch (action) {
    case RobotAction::Rotate360:
      phases_.push_back(turn(2 * kPi));
      break;
    case RobotAction::Acknowledge: {
      phases_.push_back({options_.nodS, {}, true});
      // The pointed target: along the active arm (sternum to hand), in the
      // rig's horizontal plane; turn so that it lies straight ahead.
      const PartKinematics& hand =
          features.activeHand == 1 ? features.leftHand : features.rightHand;
      if (features.valid && features.activeHand != 0) {
        const cv::Point2d dir(hand.position.x, hand.position.z);
        const double n = cv::norm(dir);
        if (n > 1e-3) {
          const double sternumX = features.head.position.x, sternumZ = features.head.position.z;
          const double tx = sternumX + options_.pointedTargetM * dir.x / n;
          const double tz = sternumZ + options_.pointedTargetM * dir.y / n;
          const double bearing = std::atan2(-tx, tz);  // positive: to the left
          if (std::abs(bearing) > 0.05) phases_.push_back(turn(bearing));
        }
      }
      break;
    }
    case RobotAction::StepLeft:
    case RobotAction::StepRight: {
      const double sign = action == RobotAction::StepLeft ? 1 : -1;
      phases_.push_back(turn(sign * kPi / 2));
      phases_.push_back({options_.stepM / v, {v, 0}, false});
      phases_.push_back(turn(-sign * kPi / 2));
      break;
    }
    case RobotAction::ComeCloser:
      phases_.push_back({options_.closerM / v, {v, 0}, false});
      break;
    case RobotAction::StopInteraction:
    case RobotAction::None:
      break;
  }
  action_ = phases_.empty() ? RobotAction::None : action;
  startS_ = timeS;
}

Behaviour::Output Behaviour::update(double timeS, std::optional<MovementClass> decision,
                                    const LmaFeatures& features) {
  Output out;
  if (decision && *decision == MovementClass::ByeBye) {
    // Honoured always: whatever runs stops now.
    phases_.clear();
    action_ = RobotAction::None;
    endS_ = timeS;
    stopped_ = true;
    out.action = RobotAction::StopInteraction;
    out.started = true;
    out.stopped = true;
    return out;
  }
  // Where the running action is.
  double t = timeS - startS_;
  const Phase* phase = nullptr;
  for (const Phase& p : phases_) {
    if (t < p.durationS) {
      phase = &p;
      break;
    }
    t -= p.durationS;
  }
  if (action_ != RobotAction::None && !phase) {
    action_ = RobotAction::None;
    phases_.clear();
    endS_ = timeS;
  }
  if (!stopped_ && action_ == RobotAction::None && decision &&
      timeS - endS_ >= options_.cooldownS) {
    start(actionFor(*decision), timeS, features);
    if (action_ != RobotAction::None) {
      out.started = true;
      phase = &phases_.front();
      t = 0;
    }
  }
  out.action = action_;
  out.stopped = stopped_;
  if (phase) {
    out.base = phase->base;
    if (phase->nod)
      out.headOffset = hw::HeadAngles{0, options_.nodRad * std::sin(kPi * t / phase->durationS), 0};
  }
  return out;
}

}  // namespace horopter
