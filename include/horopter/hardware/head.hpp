// The robot's stereo head as the vision engine sees it: commanded and measured
// pan, tilt and vergence. Drivers (Dynamixel, PTU; hardware/) and the
// synthetic scene's virtual rig implement it; the pipeline never blocks on it.
//
// Drivers: DynamixelHead (dynamixel_head.hpp, DYNAMIXEL Protocol 2.0 X series,
// with vergence) and PtuHead (ptu_head.hpp, FLIR PTU ASCII), each with a
// health() that reports timeouts, corrupt replies and a lost link; a whole
// simulated robot for the pipeline is in sim_robot.hpp.
#pragma once

#include "horopter/core/export.hpp"

#include <chrono>
#include <optional>
#include <string>

namespace horopter::hw {

using Clock = std::chrono::steady_clock;

// Radians. Pan positive turns the view to the right, tilt positive looks
// down (the rig frame of include/horopter/sim/synthetic_scene.hpp); vergence is
// the total angle between the two optical axes (0: parallel), split equally
// between the eyes on a head with two vergence axes.
struct HOROPTER_API HeadAngles {
  double pan = 0;
  double tilt = 0;
  double vergence = 0;
};

struct HOROPTER_API HeadLimits {
  double panMin = -1.5, panMax = 1.5;
  double tiltMin = -0.8, tiltMax = 0.8;
  bool hasVergence = false;  // a PTU has none: vergence commands are ignored
  double vergenceMin = 0, vergenceMax = 0;
  double maxSpeed = 1.0;  // rad/s, each axis
};

// Measured angles and when they were read.
struct HOROPTER_API HeadMeasurement {
  Clock::time_point stamp{};
  HeadAngles angles;
};

class HOROPTER_API Head {
 public:
  virtual ~Head() = default;
  virtual std::string name() const = 0;
  virtual HeadLimits limits() const = 0;
  // Non-blocking: the latest target wins. Angles outside limits() are clamped;
  // speedRadPerS 0 means the driver's default (at most limits().maxSpeed).
  virtual void command(const HeadAngles& target, double speedRadPerS = 0) = 0;
  // The latest measured angles; std::nullopt before the first reading.
  virtual std::optional<HeadMeasurement> measured() const = 0;
  // Stops every axis where it is.
  virtual void halt() = 0;
};

}  // namespace horopter::hw
