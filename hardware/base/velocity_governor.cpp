// Base safety rules: see include/horopter/hardware/velocity_governor.hpp.
#include "horopter/hardware/velocity_governor.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "horopter/core/error.hpp"

namespace horopter::hw {

namespace {

void check(double v, double hi, const char* name, const char* unit) {
  if (!(v > 0 && v <= hi))
    throw Error(std::string(name) + " must be in (0, " + std::to_string(hi) + "] " + unit +
                ", got " + std::to_string(v));
}

double approach(double from, double to, double maxStep) {
  if (to > from) return std::min(to, from + maxStep);
  return std::max(to, from - maxStep);
}

}  // namespace

void validate(const BaseSafetyLimits& l) {
  check(l.maxLinear, 10, "maxLinear", "m/s");
  check(l.maxAngular, 10, "maxAngular", "rad/s");
  check(l.maxLinearAccel, 20, "maxLinearAccel", "m/s^2");
  check(l.maxAngularAccel, 50, "maxAngularAccel", "rad/s^2");
  for (auto [v, name] :
       {std::pair{l.commandTimeout, "commandTimeout"}, std::pair{l.statusTimeout, "statusTimeout"}})
    if (v.count() < 10 || v.count() > 5000)
      throw Error(std::string(name) + " must be 10..5000 ms, got " + std::to_string(v.count()));
}

VelocityGovernor::VelocityGovernor(const BaseSafetyLimits& limits) : limits_(limits) {
  validate(limits_);
}

void VelocityGovernor::command(const BaseVelocity& v, Clock::time_point now) {
  if (!std::isfinite(v.linear) || !std::isfinite(v.angular))
    throw Error("base velocity command must be finite (got linear " + std::to_string(v.linear) +
                ", angular " + std::to_string(v.angular) + ")");
  if (estopped_) return;
  target_ = v;
  commandStamp_ = now;
  haveCommand_ = true;
}

void VelocityGovernor::emergencyStop() {
  estopped_ = true;
  haveCommand_ = false;
  target_ = {};
  lastOutput_ = {};
}

void VelocityGovernor::releaseEmergencyStop() {
  estopped_ = false;
}

BaseVelocity VelocityGovernor::output(Clock::time_point now) {
  const double dt =
      haveOutput_ ? std::max(0.0, std::chrono::duration<double>(now - lastOutputTime_).count())
                  : 0.0;
  lastOutputTime_ = now;
  haveOutput_ = true;

  const bool fresh = haveCommand_ && now - commandStamp_ <= limits_.commandTimeout;
  if (haveCommand_ && !fresh && !watchdogTripped_) {
    watchdogTripped_ = true;
    ++watchdogTrips_;
  }
  if (fresh) watchdogTripped_ = false;
  if (estopped_ || !fresh) {
    lastOutput_ = {};
    return lastOutput_;
  }
  const double wantLinear = std::clamp(target_.linear, -limits_.maxLinear, limits_.maxLinear);
  const double wantAngular = std::clamp(target_.angular, -limits_.maxAngular, limits_.maxAngular);
  lastOutput_.linear = approach(lastOutput_.linear, wantLinear, limits_.maxLinearAccel * dt);
  lastOutput_.angular = approach(lastOutput_.angular, wantAngular, limits_.maxAngularAccel * dt);
  return lastOutput_;
}

}  // namespace horopter::hw
