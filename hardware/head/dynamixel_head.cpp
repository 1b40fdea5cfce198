// DYNAMIXEL head driver: see include/horopter/hardware/dynamixel_head.hpp.
#include "horopter/hardware/dynamixel_head.hpp"

#include <algorithm>
#include <cmath>

#include "head/guarded_cycle.hpp"

namespace horopter::hw {

namespace {

// "" when a Present Position reply holds ticks the servo can report.
std::string positionProblem(const dxl::Status& s, const dxl::ServoModel& m) {
  const std::int32_t ticks = dxl::fromLittleEndian(s.data);
  if (dxl::isPositionTick(ticks, m)) return {};
  return "ID " + std::to_string(s.id) + ": present position " + std::to_string(ticks) +
         " ticks is outside " + std::to_string(m.minPositionTick) + ".." +
         std::to_string(m.maxPositionTick);
}

// "" when a Read of Velocity Limit .. Min Position Limit holds values within their ranges.
std::string limitsProblem(const dxl::Status& s, const dxl::ServoModel& m) {
  auto at = [&](std::uint16_t address) {
    return dxl::fromLittleEndian(std::span(s.data).subspan(address - m.velocityLimitAddress, 4));
  };
  const std::int32_t lo = at(m.minPositionLimitAddress), hi = at(m.maxPositionLimitAddress);
  const std::int32_t velocity = at(m.velocityLimitAddress);
  if (!dxl::isPositionTick(lo, m) || !dxl::isPositionTick(hi, m) || lo > hi)
    return "ID " + std::to_string(s.id) + ": position limits " + std::to_string(lo) + ".." +
           std::to_string(hi) + " are not within " + std::to_string(m.minPositionTick) + ".." +
           std::to_string(m.maxPositionTick);
  if (velocity < 0 || velocity > m.maxVelocityLimit)
    return "ID " + std::to_string(s.id) + ": velocity limit " + std::to_string(velocity) +
           " is outside 0.." + std::to_string(m.maxVelocityLimit);
  return {};
}

}  // namespace

DynamixelHead::DynamixelHead(std::unique_ptr<ByteTransport> transport, DynamixelHeadOptions options)
    : transport_(std::move(transport)), options_(std::move(options)) {
  if (!transport_) throw Error("DynamixelHead needs a transport");
  if (options_.leftVergenceId.has_value() != options_.rightVergenceId.has_value())
    throw Error("give both vergence servo IDs (left and right) or neither");
  if (std::abs(options_.panDirection) != 1 || std::abs(options_.tiltDirection) != 1)
    throw Error("pan/tilt direction must be +1 or -1");
  if (options_.period.count() < 5 || options_.replyTimeout.count() < 1 || options_.retries < 0)
    throw Error("DynamixelHead: period must be >= 5 ms, reply timeout >= 1 ms, retries >= 0");
  ids_ = {options_.panId, options_.tiltId};
  if (options_.leftVergenceId) {
    ids_.push_back(*options_.leftVergenceId);
    ids_.push_back(*options_.rightVergenceId);
    options_.limits.hasVergence = true;
  } else {
    options_.limits.hasVergence = false;
  }
  for (std::size_t i = 0; i < ids_.size(); ++i) {
    if (ids_[i] > 252) throw Error("DYNAMIXEL IDs are 0..252, got " + std::to_string(ids_[i]));
    if (std::find(ids_.begin(), ids_.begin() + static_cast<std::ptrdiff_t>(i), ids_[i]) !=
        ids_.begin() + static_cast<std::ptrdiff_t>(i))
      throw Error("DYNAMIXEL ID " + std::to_string(ids_[i]) +
                  " is given twice: pan, tilt and each vergence axis need a servo of their own");
  }
  for (std::uint8_t id : ids_) {
    const auto replies = exchange(dxl::pingPacket(id), {id}, 3);
    if (replies.empty())
      throw Error("DYNAMIXEL ID " + std::to_string(id) + " does not answer on " +
                  transport_->describe() +
                  ": check the ID, the baud rate (X series default 57600) "
                  "and the power (" +
                  health().lastFault + ")");
    modelNumbers_.push_back(dxl::fromLittleEndian(std::span(replies[0].data).first(2)));
  }
  readServoLimits();
  for (std::uint8_t id : ids_) {
    const std::vector<std::uint8_t> one = {1};
    if (exchange(dxl::writePacket(id, options_.model.torqueEnableAddress, one), {id}, 0).empty())
      throw Error("DYNAMIXEL ID " + std::to_string(id) + " did not acknowledge Torque Enable (" +
                  health().lastFault + ")");
  }
  const std::vector<std::int32_t> ticks = readPresentTicks();
  if (!ticks.empty()) {
    lastTicks_ = ticks;
    measured_ = HeadMeasurement{Clock::now(), anglesFromTicks(ticks)};
    target_ = measured_->angles;
  }
  worker_.start(options_.period, [this] { runGuardedCycle([this] { cycle(); }, mutex_, health_); });
}

DynamixelHead::~DynamixelHead() {
  shutdown();
}

// Velocity Limit, Max and Min Position Limit are consecutive (44, 48, 52 on the X series).
void DynamixelHead::readServoLimits() {
  const auto& m = options_.model;
  const std::uint16_t first = m.velocityLimitAddress;
  const std::uint16_t length = static_cast<std::uint16_t>(m.minPositionLimitAddress + 4 - first);
  HeadLimits& l = options_.limits;
  auto axis = [&](std::uint8_t id, int direction, double& lo, double& hi) {
    const auto r = exchange(dxl::readPacket(id, first, length), {id}, length,
                            [&m](const dxl::Status& s) { return limitsProblem(s, m); });
    if (r.empty())
      throw Error("DYNAMIXEL ID " + std::to_string(id) + " did not return its limits (Read " +
                  std::to_string(first) + ", " + std::to_string(length) +
                  " bytes): " + health().lastFault);
    const auto& d = r[0].data;
    auto at = [&](std::uint16_t address) {
      return dxl::fromLittleEndian(std::span(d).subspan(address - first, 4));
    };
    const double a = direction * dxl::ticksToRadians(at(m.minPositionLimitAddress), m);
    const double b = direction * dxl::ticksToRadians(at(m.maxPositionLimitAddress), m);
    lo = std::max(lo, std::min(a, b));
    hi = std::min(hi, std::max(a, b));
    const std::int32_t velocity = at(m.velocityLimitAddress);
    if (velocity > 0)
      l.maxSpeed = std::min(l.maxSpeed, dxl::velocityUnitsToRadPerSecond(velocity, m));
  };
  axis(options_.panId, options_.panDirection, l.panMin, l.panMax);
  axis(options_.tiltId, options_.tiltDirection, l.tiltMin, l.tiltMax);
  if (l.panMin > l.panMax || l.tiltMin > l.tiltMax)
    throw Error("the requested head limits do not overlap the servos' Min/Max Position Limits");
}

std::string DynamixelHead::name() const {
  return "DYNAMIXEL head (" + options_.model.family + ") on " + transport_->describe();
}

void DynamixelHead::command(const HeadAngles& target, double speedRadPerS) {
  if (!std::isfinite(target.pan) || !std::isfinite(target.tilt) ||
      !std::isfinite(target.vergence) || !std::isfinite(speedRadPerS) || speedRadPerS < 0)
    throw Error("head command must be finite angles and a speed >= 0");
  const HeadLimits& l = options_.limits;
  std::lock_guard lock(mutex_);
  target_.pan = std::clamp(target.pan, l.panMin, l.panMax);
  target_.tilt = std::clamp(target.tilt, l.tiltMin, l.tiltMax);
  target_.vergence = l.hasVergence ? std::clamp(target.vergence, l.vergenceMin, l.vergenceMax) : 0;
  const double want = speedRadPerS > 0 ? speedRadPerS : options_.defaultSpeed;
  speed_ = std::min(want, l.maxSpeed);
  haltRequested_ = false;
  ++targetGeneration_;
}

std::optional<HeadMeasurement> DynamixelHead::measured() const {
  std::lock_guard lock(mutex_);
  return measured_;
}

void DynamixelHead::halt() {
  std::lock_guard lock(mutex_);
  haltRequested_ = true;
}

HeadHealth DynamixelHead::health() const {
  std::lock_guard lock(mutex_);
  return health_;
}

std::vector<std::pair<std::uint8_t, std::int32_t>> DynamixelHead::goalTicks(
    const HeadAngles& a) const {
  const auto& m = options_.model;
  std::vector<std::pair<std::uint8_t, std::int32_t>> v = {
      {options_.panId, dxl::radiansToTicks(options_.panDirection * a.pan, m)},
      {options_.tiltId, dxl::radiansToTicks(options_.tiltDirection * a.tilt, m)}};
  if (options_.leftVergenceId) {
    v.push_back({*options_.leftVergenceId, dxl::radiansToTicks(a.vergence / 2, m)});
    v.push_back({*options_.rightVergenceId, dxl::radiansToTicks(-a.vergence / 2, m)});
  }
  return v;
}

HeadAngles DynamixelHead::anglesFromTicks(const std::vector<std::int32_t>& t) const {
  const auto& m = options_.model;
  HeadAngles a;
  a.pan = options_.panDirection * dxl::ticksToRadians(t[0], m);
  a.tilt = options_.tiltDirection * dxl::ticksToRadians(t[1], m);
  if (t.size() >= 4) a.vergence = dxl::ticksToRadians(t[2], m) - dxl::ticksToRadians(t[3], m);
  return a;
}

// Sends `request`, collects one status packet from each of `ids` (in order),
// each with `dataLength` data bytes that `check` (if any) accepts. Anything
// else is a counted fault and the request is sent again. Empty result: failed
// after the retries (the reason is in health()).
std::vector<dxl::Status> DynamixelHead::exchange(const std::vector<std::uint8_t>& request,
                                                 const std::vector<std::uint8_t>& ids,
                                                 std::size_t dataLength, const StatusCheck& check) {
  std::string why;
  for (int attempt = 0; attempt <= options_.retries; ++attempt) {
    transport_->discardInput();
    rx_.clear();
    transport_->write(request);
    std::vector<dxl::Status> got;
    bool corrupt = false;
    const auto deadline = Clock::now() + options_.replyTimeout *
                                             static_cast<int>(std::max<std::size_t>(1, ids.size()));
    while (got.size() < ids.size() && !corrupt) {
      const dxl::ParseResult r = dxl::parsePacket(rx_);
      rx_.erase(rx_.begin(), rx_.begin() + static_cast<std::ptrdiff_t>(r.consumed));
      if (r.outcome == dxl::ParseOutcome::kCorrupt) {
        corrupt = true;
        why = r.error;
        break;
      }
      if (r.outcome == dxl::ParseOutcome::kPacket) {
        if (r.packet.instruction != dxl::inst::kStatus)
          continue;  // our own echo on a half-duplex adapter
        if (r.packet.params.empty()) {
          corrupt = true;
          why = "status packet from ID " + std::to_string(r.packet.id) + " has no ERROR byte";
          break;
        }
        const dxl::Status s = dxl::toStatus(r.packet);
        if (s.id != ids[got.size()]) continue;
        got.push_back(s);
        continue;
      }
      const auto now = Clock::now();
      if (now >= deadline) break;
      const auto left = std::chrono::ceil<std::chrono::milliseconds>(deadline - now);
      const auto more = transport_->read(256, left);
      rx_.insert(rx_.end(), more.begin(), more.end());
    }
    std::lock_guard lock(mutex_);
    if (corrupt) {
      ++health_.corruptReplies;
      health_.lastFault = "corrupt reply: " + why;
      continue;
    }
    if (got.size() < ids.size()) {
      ++health_.timeouts;
      why = "no reply from ID " + std::to_string(ids[got.size()]) + " within " +
            std::to_string(options_.replyTimeout.count()) + " ms";
      health_.lastFault = why;
      continue;
    }
    bool deviceError = false;
    for (const auto& s : got)
      if (s.error & 0x7F) {
        ++health_.deviceErrors;
        health_.lastFault = "ID " + std::to_string(s.id) + ": " + dxl::describeError(s.error);
        deviceError = true;
      }
    if (deviceError) continue;
    std::string bad;
    for (const auto& s : got) {
      if (s.data.size() != dataLength)
        bad = "ID " + std::to_string(s.id) + ": " + std::to_string(s.data.size()) +
              " data bytes, expected " + std::to_string(dataLength);
      else if (check)
        bad = check(s);
      if (!bad.empty()) break;
    }
    if (!bad.empty()) {
      ++health_.corruptReplies;
      health_.lastFault = "implausible reply: " + bad;
      continue;
    }
    ++health_.exchanges;
    return got;
  }
  return {};
}

std::vector<std::int32_t> DynamixelHead::readPresentTicks() {
  const auto& m = options_.model;
  const auto replies = exchange(dxl::syncReadPacket(m.presentPositionAddress, 4, ids_), ids_, 4,
                                [&m](const dxl::Status& s) { return positionProblem(s, m); });
  std::vector<std::int32_t> ticks;
  for (const auto& s : replies)
    ticks.push_back(dxl::fromLittleEndian(s.data));
  return ticks;
}

void DynamixelHead::fail(const std::string& what) {
  std::lock_guard lock(mutex_);
  health_.lastFault = what;
  if (++failuresInARow_ >= options_.linkLostAfter) health_.linkUp = false;
}

void DynamixelHead::cycle() {
  HeadAngles target;
  double speed;
  long generation;
  bool haltNow;
  {
    std::lock_guard lock(mutex_);
    target = target_;
    speed = speed_;
    generation = targetGeneration_;
    haltNow = haltRequested_;
    haltRequested_ = false;
  }
  const auto& m = options_.model;
  if (haltNow && !lastTicks_.empty()) {
    std::vector<std::pair<std::uint8_t, std::int32_t>> hold;
    for (std::size_t i = 0; i < ids_.size(); ++i)
      hold.push_back({ids_[i], lastTicks_[i]});
    transport_->write(dxl::syncWritePacket(m.goalPositionAddress, 4, hold));
    sentGeneration_ = generation;
  } else if (generation != sentGeneration_) {
    const std::int32_t units = dxl::radPerSecondToVelocityUnits(speed, m);
    std::vector<std::pair<std::uint8_t, std::int32_t>> velocities;
    for (std::uint8_t id : ids_)
      velocities.push_back({id, units});
    transport_->write(dxl::syncWritePacket(m.profileVelocityAddress, 4, velocities));
    transport_->write(dxl::syncWritePacket(m.goalPositionAddress, 4, goalTicks(target)));
    sentGeneration_ = generation;
  }
  const std::vector<std::int32_t> ticks = readPresentTicks();
  if (ticks.empty()) {
    fail(health().lastFault);
    return;
  }
  lastTicks_ = ticks;
  std::lock_guard lock(mutex_);
  measured_ = HeadMeasurement{Clock::now(), anglesFromTicks(ticks)};
  failuresInARow_ = 0;
  health_.linkUp = true;
}

void DynamixelHead::shutdown() {
  if (!worker_.stop()) return;
  // Hold where it is (best effort): the servos keep torque and stop moving.
  try {
    if (!lastTicks_.empty()) {
      std::vector<std::pair<std::uint8_t, std::int32_t>> hold;
      for (std::size_t i = 0; i < ids_.size(); ++i)
        hold.push_back({ids_[i], lastTicks_[i]});
      transport_->write(dxl::syncWritePacket(options_.model.goalPositionAddress, 4, hold));
    }
  } catch (const LinkError&) {
  }
}

}  // namespace horopter::hw
