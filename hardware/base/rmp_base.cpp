// Segway RMP driver: see include/horopter/hardware/rmp_base.hpp.
#include "horopter/hardware/rmp_base.hpp"

#include <cmath>

namespace horopter::hw {

namespace {
constexpr unsigned kFullSeries = 0xFF;  // 0x400..0x407 all seen
}

RmpBase::RmpBase(std::unique_ptr<CanTransport> transport, RmpBaseOptions options)
    : transport_(std::move(transport)), options_(options), governor_(options.limits) {
  if (!transport_) throw Error("RmpBase needs a CAN transport");
  if (options_.period.count() < 5 || options_.period.count() > 200)
    throw Error("RMP command period must be 5..200 ms, got " +
                std::to_string(options_.period.count()));
  if (options_.resetIntegratorsAtStart) {
    // libsegwayrmp resetAllIntegrators(): command 0x32 with parameters 1, 2, 4, 8.
    try {
      for (std::uint16_t p : {1, 2, 4, 8})
        send(rmp::encodeConfig(rmp::ConfigCommand::kResetIntegrators, p));
    } catch (const LinkError& e) {
      throw Error(std::string("cannot talk to the RMP: ") + e.what());
    }
  }
  if (options_.startThread) worker_.start(options_.period, [this] { step(options_.clock()); });
}

RmpBase::~RmpBase() {
  shutdown();
}

std::string RmpBase::name() const {
  return std::string("Segway ") + options_.scaling.model + " on " + transport_->describe();
}

void RmpBase::command(const BaseVelocity& velocity) {
  std::lock_guard lock(mutex_);
  governor_.command(velocity, options_.clock());
}

void RmpBase::emergencyStop() {
  {
    std::lock_guard lock(mutex_);
    governor_.emergencyStop();
    health_.lastFault = "emergency stop";
  }
  worker_.kick();  // send the zero now, not at the next tick
}

void RmpBase::releaseEmergencyStop() {
  std::lock_guard lock(mutex_);
  governor_.releaseEmergencyStop();
}

bool RmpBase::emergencyStopped() const {
  std::lock_guard lock(mutex_);
  return governor_.emergencyStopped();
}

std::optional<Odometry> RmpBase::odometry() const {
  std::lock_guard lock(mutex_);
  return odometry_;
}

BaseHealth RmpBase::health() const {
  std::lock_guard lock(mutex_);
  BaseHealth h = health_;
  h.watchdogTripped = governor_.watchdogTripped();
  h.watchdogTrips = governor_.watchdogTrips();
  return h;
}

std::optional<rmp::Status> RmpBase::lastStatus() const {
  std::lock_guard lock(mutex_);
  return status_;
}

void RmpBase::send(const CanFrame& frame) {
  transport_->send(frame);
}

void RmpBase::completeSeries(Clock::time_point now) {
  // Called with mutex_ held.
  const rmp::Status& s = partial_;
  if (!odometry_) {
    odometry_ = Odometry{};
  } else {
    const double dForward = s.foreAftDisplacement - lastForeAft_;
    const double dYaw = s.yawDisplacement - lastYaw_;
    const double mid = odometry_->heading + dYaw / 2;
    odometry_->x += dForward * std::cos(mid);
    odometry_->y += dForward * std::sin(mid);
    odometry_->heading += dYaw;
  }
  lastForeAft_ = s.foreAftDisplacement;
  lastYaw_ = s.yawDisplacement;
  odometry_->stamp = now;
  odometry_->velocity = {(s.leftWheelSpeed + s.rightWheelSpeed) / 2, s.yawRate};
  status_ = s;
  lastSeries_ = now;
  ++health_.seriesReceived;
}

void RmpBase::receiveAll(Clock::time_point now) {
  CanFrame f;
  // Bounded: a flooded bus must not keep the cycle from sending its command.
  for (int n = 0; n < 512 && transport_->receive(f, std::chrono::milliseconds(0)); ++n) {
    std::lock_guard lock(mutex_);
    if (const auto enabled = rmp::decodeMotorStatus(f)) {
      if (health_.motorsEnabled.value_or(true) && !*enabled)
        health_.lastFault = "the RMP reports its motors disabled (its e-stop is pressed)";
      health_.motorsEnabled = *enabled;
      continue;
    }
    if (f.id == rmp::kStatusFirstId) {  // a new series starts
      partial_.receivedMask = 0;
      partialHasBadFrame_ = false;
    }
    try {
      if (!rmp::decodeStatusFrame(f, options_.scaling, partial_)) continue;
    } catch (const Error& e) {
      // Wrong length or implausible values: counted, never used (the series
      // stays incomplete, so odometry skips it).
      ++health_.badFrames;
      health_.lastFault = e.what();
      partialHasBadFrame_ = true;
      continue;
    }
    if (f.id == rmp::kStatusLastId) {
      if ((partial_.receivedMask & kFullSeries) == kFullSeries) {
        completeSeries(now);
      } else if (!partialHasBadFrame_) {  // a bad frame was counted and named already
        ++health_.badFrames;
        health_.lastFault = "incomplete RMP status series (frames missing)";
      }
      partial_.receivedMask = 0;
      partialHasBadFrame_ = false;
    }
  }
}

void RmpBase::step(Clock::time_point now) {
  std::lock_guard stepLock(stepMutex_);
  {
    std::lock_guard lock(mutex_);
    if (!started_) {
      start_ = now;
      started_ = true;
    }
  }
  try {
    receiveAll(now);
  } catch (const LinkError& e) {
    std::lock_guard lock(mutex_);
    health_.linkUp = false;
    health_.lastFault = e.what();
  }
  BaseVelocity out;
  {
    std::lock_guard lock(mutex_);
    const auto since = health_.seriesReceived > 0 ? now - lastSeries_ : now - start_;
    const bool fresh = health_.seriesReceived > 0 && since <= options_.limits.statusTimeout;
    const bool startGrace = health_.seriesReceived == 0 && since <= options_.limits.statusTimeout;
    if (!fresh && !startGrace && !staleReported_) {
      ++health_.statusTimeouts;
      staleReported_ = true;
      health_.lastFault =
          "no status from the RMP for " +
          std::to_string(std::chrono::duration_cast<std::chrono::milliseconds>(since).count()) +
          " ms: commanding zero velocity";
    }
    if (fresh) staleReported_ = false;
    health_.statusFresh = fresh;
    out = governor_.output(now);
    // Moving blind is not allowed: zero until the base reports again (a stale
    // start, before any report, counts too).
    if (!fresh) {
      governor_.forceStop();
      out = {};
    }
    health_.lastSent = out;
  }
  try {
    send(rmp::encodeMotion(out, options_.scaling));
    std::lock_guard lock(mutex_);
    ++health_.framesSent;
  } catch (const LinkError& e) {
    std::lock_guard lock(mutex_);
    health_.linkUp = false;
    health_.lastFault = e.what();
  }
}

void RmpBase::shutdown() {
  if (!worker_.stop()) return;
  std::lock_guard stepLock(stepMutex_);
  try {
    send(rmp::encodeMotion({}, options_.scaling));
    std::lock_guard lock(mutex_);
    health_.lastSent = {};
  } catch (const LinkError&) {
    // The link is gone: the RMP stops on its own when commands stop arriving.
  }
}

}  // namespace horopter::hw
