// The base's safety rules as a pure state machine, time passed in (so the
// tests drive it with a fake clock): command watchdog, velocity and
// acceleration limits, latching emergency stop.
//
//   - A command older than commandTimeout (default 200 ms) -> zero velocity
//     (the watchdog trips and counts; the next fresh command clears it).
//   - Every output is clamped to |linear| <= maxLinear, |angular| <= maxAngular.
//   - Changes toward a command are limited to maxLinearAccel / maxAngularAccel
//     per second. Stops (watchdog, e-stop, lost link) go to zero at once:
//     braking is the base's own controller's job, and a safety stop must not
//     wait for a ramp.
//   - emergencyStop() latches: zero until releaseEmergencyStop(); commands
//     received meanwhile are dropped, so the base does not lurch off on release.
#pragma once

#include "horopter/core/export.hpp"

#include <chrono>

#include "horopter/hardware/base.hpp"

namespace horopter::hw {

struct HOROPTER_API BaseSafetyLimits {
  double maxLinear = 0.5;                         // m/s, (0, 10]
  double maxAngular = 1.0;                        // rad/s, (0, 10]
  double maxLinearAccel = 0.5;                    // m/s^2, (0, 20]
  double maxAngularAccel = 2.0;                   // rad/s^2, (0, 50]
  std::chrono::milliseconds commandTimeout{200};  // watchdog, 10 .. 5000 ms
  std::chrono::milliseconds statusTimeout{500};   // base's reports, 10 .. 5000 ms
};

// Throws horopter::Error naming the first value out of range.
HOROPTER_API void validate(const BaseSafetyLimits& limits);

class HOROPTER_API VelocityGovernor {
 public:
  explicit VelocityGovernor(const BaseSafetyLimits& limits);

  // Throws horopter::Error for a non-finite velocity. Ignored while e-stopped.
  void command(const BaseVelocity& velocity, Clock::time_point now);
  void emergencyStop();
  void releaseEmergencyStop();
  bool emergencyStopped() const { return estopped_; }
  // Forces zero (lost link, shutdown) without latching.
  void forceStop() { lastOutput_ = {}; }

  // The velocity to send at `now`.
  BaseVelocity output(Clock::time_point now);
  bool watchdogTripped() const { return watchdogTripped_; }
  long watchdogTrips() const { return watchdogTrips_; }
  const BaseSafetyLimits& limits() const { return limits_; }

 private:
  BaseSafetyLimits limits_;
  BaseVelocity target_;
  bool haveCommand_ = false;
  Clock::time_point commandStamp_{};
  BaseVelocity lastOutput_;
  Clock::time_point lastOutputTime_{};
  bool haveOutput_ = false;
  bool estopped_ = false;
  bool watchdogTripped_ = false;
  long watchdogTrips_ = 0;
};

}  // namespace horopter::hw
