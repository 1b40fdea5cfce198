// The robot's mobile base as the vision engine sees it: velocity commands
// in, odometry out, a latching emergency stop. The Segway RMP driver
// (hardware/) and its simulator implement it.
//
// Driver: RmpBase (rmp_base.hpp) over SocketCAN, the RMP's USB interface or
// the in-process bus of the simulated RMP; its safety rules (watchdog,
// velocity and acceleration limits, e-stop) are VelocityGovernor
// (velocity_governor.hpp); health() reports watchdog trips, status timeouts,
// bad frames, the RMP's own e-stop and a lost link.
#pragma once

#include "horopter/core/export.hpp"

#include <chrono>
#include <optional>
#include <string>

namespace horopter::hw {

using Clock = std::chrono::steady_clock;

// SI units: linear m/s forward, angular rad/s, positive turns left
// (counter-clockwise seen from above).
struct HOROPTER_API BaseVelocity {
  double linear = 0;
  double angular = 0;
};

// Integrated from the base's own reports: x forward and y left of the pose
// at start, heading counter-clockwise, in metres and radians.
struct HOROPTER_API Odometry {
  Clock::time_point stamp{};
  double x = 0, y = 0, heading = 0;
  BaseVelocity velocity;  // measured
};

class HOROPTER_API Base {
 public:
  virtual ~Base() = default;
  virtual std::string name() const = 0;
  // Non-blocking: the latest command wins. Commands must keep coming: with
  // none fresher than the watchdog period (200 ms) the base is stopped.
  virtual void command(const BaseVelocity& velocity) = 0;
  // Latching: zero velocity until releaseEmergencyStop(); commands are ignored meanwhile.
  virtual void emergencyStop() = 0;
  virtual void releaseEmergencyStop() = 0;
  virtual bool emergencyStopped() const = 0;
  // std::nullopt before the first status report.
  virtual std::optional<Odometry> odometry() const = 0;
};

}  // namespace horopter::hw
