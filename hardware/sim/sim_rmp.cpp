// Simulated Segway RMP: see include/horopter/hardware/sim_rmp.hpp.
#include "horopter/hardware/sim_rmp.hpp"

#include <cmath>

namespace horopter::hw {

SimRmp::SimRmp(CanTransport& bus, SimRmpOptions options) : bus_(bus), options_(options) {
  reported_.operationalMode = 1;  // tractor
  reported_.uiBatteryVolts = 7.4;
  reported_.powerbaseBatteryVolts = 72.0;
  if (options_.startThread) thread_ = std::thread([this] { run(); });
}

SimRmp::~SimRmp() {
  stop();
}

void SimRmp::stop() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
}

void SimRmp::injectFault(SimRmpFault fault, int series) {
  std::lock_guard lock(mutex_);
  fault_ = fault;
  faultSeries_ = series;
}

void SimRmp::pressEmergencyStop(bool pressed) {
  std::lock_guard lock(mutex_);
  buttonPressed_ = pressed;
}

SimRmpTruth SimRmp::truth() const {
  std::lock_guard lock(mutex_);
  return truth_;
}

void SimRmp::step(Clock::time_point now) {
  CanFrame f;
  try {
    while (bus_.receive(f, std::chrono::milliseconds(0))) {
      if (f.id != rmp::kCommandId || f.length != 8) continue;
      const rmp::MotionCounts c = rmp::decodeMotion(f);
      std::lock_guard lock(mutex_);
      ++truth_.motionFrames;
      if (c.configCommand == static_cast<std::uint16_t>(rmp::ConfigCommand::kResetIntegrators)) {
        if (c.configParameter & 1) reported_.rightWheelDisplacement = 0;
        if (c.configParameter & 2) reported_.leftWheelDisplacement = 0;
        if (c.configParameter & 4) reported_.yawDisplacement = 0;
        if (c.configParameter & 8) reported_.foreAftDisplacement = 0;
        ++truth_.resets;
      }
      commanded_ = rmp::countsToVelocity(c, options_.scaling);
      reported_.commandedVelocity = commanded_.linear;
      reported_.commandedYawRateCounts = c.yawRate;
    }
  } catch (const LinkError&) {
    return;  // unplugged: a real RMP would stop; nothing to report to
  }
  std::array<CanFrame, 8> frames;
  SimRmpFault fault;
  bool enabled;
  {
    std::lock_guard lock(mutex_);
    const double dt = haveTime_ ? std::chrono::duration<double>(now - last_).count() : 0.0;
    last_ = now;
    haveTime_ = true;
    // Kinematic unicycle: the base follows the command (the driver limits acceleration).
    const BaseVelocity v = buttonPressed_ ? BaseVelocity{} : commanded_;
    const double mid = truth_.heading + v.angular * dt / 2;
    truth_.x += v.linear * dt * std::cos(mid);
    truth_.y += v.linear * dt * std::sin(mid);
    truth_.heading += v.angular * dt;
    truth_.velocity = v;
    const double half = options_.trackWidth / 2;
    reported_.leftWheelSpeed = v.linear - v.angular * half;
    reported_.rightWheelSpeed = v.linear + v.angular * half;
    reported_.yawRate = v.angular;
    reported_.leftWheelDisplacement += reported_.leftWheelSpeed * dt;
    reported_.rightWheelDisplacement += reported_.rightWheelSpeed * dt;
    reported_.foreAftDisplacement += v.linear * dt;
    reported_.yawDisplacement += v.angular * dt;
    reported_.servoFrames += dt;
    if (reported_.servoFrames > 600) reported_.servoFrames -= 600;
    frames = rmp::encodeStatusFrames(reported_, options_.scaling);
    enabled = !buttonPressed_;
    fault = faultSeries_ > 0 ? fault_ : SimRmpFault::kNone;
    if (faultSeries_ > 0) --faultSeries_;
  }
  if (fault == SimRmpFault::kSilent) return;
  try {
    for (CanFrame& fr : frames) {
      if (fault == SimRmpFault::kMissingFrame && fr.id == 0x404) continue;
      if (fault == SimRmpFault::kBadLength && fr.id == 0x402) fr.length = 3;
      if (fault == SimRmpFault::kWildValues && fr.id == 0x402) {
        fr.data[0] = fr.data[2] = 0x7F;
        fr.data[1] = fr.data[3] = 0xFF;
      }
      if (fault == SimRmpFault::kWildValues && fr.id == 0x406) fr.data[1] = 9;
      bus_.send(fr);
    }
    bus_.send(rmp::encodeMotorStatus(enabled));
  } catch (const LinkError&) {
  }
}

void SimRmp::run() {
  auto next = Clock::now();
  while (!stop_) {
    step(Clock::now());
    next += options_.period;
    std::this_thread::sleep_until(next);
  }
}

}  // namespace horopter::hw
