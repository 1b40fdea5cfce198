// The behaviour layer: movement decisions to robot actions (the paper's
// Table II), as per-frame base velocities and head gestures.
//
//   circle         -> Rotate360:       turn on the spot, one full turn
//   pointing       -> Acknowledge:     nod, then turn towards the pointed direction
//   wave left      -> StepLeft:        a side step to the robot's own left (turn
//                                      90 degrees left, drive, turn back)
//   wave right     -> StepRight:       the same to the right
//   sagittal wave  -> ComeCloser:      drive towards the person
//   bye-bye        -> StopInteraction: zero velocity now, whatever runs; later
//                                      decisions are ignored until resume()
//
// One movement gives one action: decisions that come while an action runs,
// or within `cooldownS` after it ended, are ignored; a bye-bye is honoured
// always, at once.
#pragma once

#include "horopter/core/export.hpp"

#include <optional>
#include <vector>

#include "horopter/hardware/base.hpp"
#include "horopter/hardware/head.hpp"
#include "horopter/movement/lma.hpp"
#include "horopter/movement/movement.hpp"

namespace horopter {

struct HOROPTER_API BehaviourOptions {
  double cooldownS = 1.5;         // after an action ends, new decisions are ignored this long
  double turnSpeedRadPerS = 0.8;  // base, turning on the spot
  double driveSpeedMps = 0.15;    // base, forward
  double stepM = 0.3;             // the side step's length
  double closerM = 0.3;           // how far "come closer" drives
  double nodRad = 0.2;            // the acknowledging nod's tilt
  double nodS = 0.8;              // and its duration
  double pointedTargetM = 2.0;    // the pointed target: this far along the arm from the person
};

// Table II.
HOROPTER_API RobotAction actionFor(MovementClass movement);

class HOROPTER_API Behaviour {
 public:
  explicit Behaviour(BehaviourOptions options = {});  // throws horopter::Error for bad options

  struct Output {
    RobotAction action = RobotAction::None;    // running now
    bool started = false;                      // it started on this call
    bool stopped = false;                      // the interaction is stopped (bye-bye)
    hw::BaseVelocity base;                     // command this now
    std::optional<hw::HeadAngles> headOffset;  // added to the head's tracking command
  };
  // Once per frame, times increasing. `features` gives the pointed direction.
  Output update(double timeS, std::optional<MovementClass> decision, const LmaFeatures& features);
  // Accept actions again after a bye-bye (a new godfather, an operator).
  void resume();
  bool stopped() const { return stopped_; }

 private:
  struct Phase {
    double durationS = 0;
    hw::BaseVelocity base;
    bool nod = false;
  };
  void start(RobotAction action, double timeS, const LmaFeatures& features);

  BehaviourOptions options_;
  RobotAction action_ = RobotAction::None;
  std::vector<Phase> phases_;
  double startS_ = 0;
  double endS_ = -1e300;  // when the last action ended
  bool stopped_ = false;
};

}  // namespace horopter
