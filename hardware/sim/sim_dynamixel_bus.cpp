// Simulated DYNAMIXEL bus on a pty: see include/horopter/hardware/sim_devices.hpp.
#include <algorithm>
#include <cmath>

#include "horopter/hardware/sim_devices.hpp"

namespace horopter::hw {

namespace {
constexpr std::uint16_t kModelNumber = 1020;  // XM430-W350
constexpr std::uint8_t kFirmware = 45;
}  // namespace

SimDynamixelBus::SimDynamixelBus(std::vector<std::uint8_t> ids, dxl::ServoModel model)
    : model_(std::move(model)) {
  for (std::uint8_t id : ids) {
    Servo s;
    s.position = model_.centreTick;
    s.goal = model_.centreTick;
    servos_[id] = s;
  }
  thread_ = std::thread([this] { run(); });
}

SimDynamixelBus::~SimDynamixelBus() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
}

void SimDynamixelBus::injectFault(DeviceFault fault, int count) {
  std::lock_guard lock(mutex_);
  fault_ = fault;
  faultCount_ = count;
}

void SimDynamixelBus::injectStatus(std::vector<std::uint8_t> params, int count) {
  std::lock_guard lock(mutex_);
  injectedParams_ = std::move(params);
  injectedCount_ = count;
}

double SimDynamixelBus::positionRad(std::uint8_t id) const {
  std::lock_guard lock(mutex_);
  return dxl::ticksToRadians(static_cast<std::int32_t>(std::lround(servos_.at(id).position)),
                             model_);
}

std::int32_t SimDynamixelBus::goalTicks(std::uint8_t id) const {
  std::lock_guard lock(mutex_);
  return servos_.at(id).goal;
}

void SimDynamixelBus::setLimits(std::uint8_t id, std::int32_t minTicks, std::int32_t maxTicks,
                                std::int32_t velocityLimit) {
  std::lock_guard lock(mutex_);
  Servo& s = servos_.at(id);
  s.minLimit = minTicks;
  s.maxLimit = maxTicks;
  s.velocityLimit = velocityLimit;
}

bool SimDynamixelBus::torqueOn(std::uint8_t id) const {
  std::lock_guard lock(mutex_);
  return servos_.at(id).torque;
}

void SimDynamixelBus::advance(double seconds) {
  for (auto& [id, s] : servos_) {
    if (!s.torque) continue;
    const std::int32_t units =
        s.profileVelocity > 0 ? std::min(s.profileVelocity, s.velocityLimit) : s.velocityLimit;
    const double speed = units * model_.velocityUnitRpm / 60.0 * model_.ticksPerTurn;
    const double step = speed * seconds;
    const double d = s.goal - s.position;
    s.position = std::abs(d) <= step ? s.goal : s.position + (d > 0 ? step : -step);
  }
}

std::vector<std::uint8_t> SimDynamixelBus::readTable(const Servo& s, std::uint16_t address,
                                                     std::uint16_t length) const {
  std::vector<std::uint8_t> table(256, 0);
  auto put = [&](std::uint16_t at, std::int32_t v, std::size_t n) {
    const auto b = dxl::littleEndian(v, n);
    std::copy(b.begin(), b.end(), table.begin() + at);
  };
  put(0, kModelNumber, 2);
  table[6] = kFirmware;
  put(model_.velocityLimitAddress, s.velocityLimit, 4);
  put(model_.maxPositionLimitAddress, s.maxLimit, 4);
  put(model_.minPositionLimitAddress, s.minLimit, 4);
  put(model_.torqueEnableAddress, s.torque ? 1 : 0, 1);
  put(model_.profileVelocityAddress, s.profileVelocity, 4);
  put(model_.goalPositionAddress, s.goal, 4);
  put(model_.presentPositionAddress, static_cast<std::int32_t>(std::lround(s.position)), 4);
  std::vector<std::uint8_t> out;
  for (std::uint16_t i = 0; i < length; ++i)
    out.push_back(address + i < table.size() ? table[address + i] : 0);
  return out;
}

void SimDynamixelBus::writeTable(Servo& s, std::uint16_t address,
                                 std::span<const std::uint8_t> data) {
  const std::int32_t v = dxl::fromLittleEndian(data);
  if (address == model_.torqueEnableAddress && data.size() >= 1) s.torque = data[0] != 0;
  if (address == model_.profileVelocityAddress && data.size() == 4) s.profileVelocity = v;
  if (address == model_.goalPositionAddress && data.size() == 4)
    s.goal = std::clamp(v, s.minLimit, s.maxLimit);
}

void SimDynamixelBus::reply(std::vector<std::uint8_t> bytes) {
  DeviceFault f = DeviceFault::kNone;
  {
    std::lock_guard lock(mutex_);
    if (injectedCount_ > 0 && bytes.size() > 7 && bytes[7] == dxl::inst::kStatus) {
      --injectedCount_;
      bytes = dxl::encodePacket(bytes[4], dxl::inst::kStatus, injectedParams_);
    }
    if (faultCount_ > 0) {
      f = fault_;
      --faultCount_;
    }
  }
  switch (f) {
    case DeviceFault::kNone:
      break;
    case DeviceFault::kCorruptChecksum:
      bytes.back() ^= 0x5A;
      break;
    case DeviceFault::kShortFrame:
      bytes.resize(bytes.size() / 2);
      break;
    case DeviceFault::kGarbage:
      for (std::size_t i = 0; i < bytes.size(); ++i)
        bytes[i] = static_cast<std::uint8_t>(0x37 * i + 11);
      break;
    case DeviceFault::kNoReply:
      return;
    case DeviceFault::kDisconnect:
      pty_.closeMaster();
      return;
  }
  pty_.write(bytes);
}

void SimDynamixelBus::handle(const dxl::Packet& p) {
  const auto& prm = p.params;
  auto u16 = [&](std::size_t at) {
    return static_cast<std::uint16_t>(prm[at] | (prm[at + 1] << 8));
  };
  std::vector<std::vector<std::uint8_t>> replies;
  {
    std::lock_guard lock(mutex_);
    auto servo = servos_.find(p.id);
    const bool mine = servo != servos_.end();
    switch (p.instruction) {
      case dxl::inst::kPing:
        for (auto& [id, s] : servos_)
          if (id == p.id || p.id == dxl::kBroadcastId) {
            auto data = dxl::littleEndian(kModelNumber, 2);
            data.push_back(kFirmware);
            replies.push_back(dxl::statusPacket(id, 0, data));
          }
        break;
      case dxl::inst::kRead:
        if (mine && prm.size() == 4)
          replies.push_back(dxl::statusPacket(p.id, 0, readTable(servo->second, u16(0), u16(2))));
        else if (mine)
          replies.push_back(dxl::statusPacket(p.id, 5, {}));  // data length error
        break;
      case dxl::inst::kWrite:
        if (mine && prm.size() >= 3) {
          writeTable(servo->second, u16(0), std::span(prm).subspan(2));
          replies.push_back(dxl::statusPacket(p.id, 0, {}));
        } else if (mine) {
          replies.push_back(dxl::statusPacket(p.id, 5, {}));
        }
        break;
      case dxl::inst::kSyncWrite: {
        if (prm.size() < 4) break;
        const std::uint16_t address = u16(0), length = u16(2);
        for (std::size_t at = 4; at + 1 + length <= prm.size(); at += 1 + length) {
          auto s = servos_.find(prm[at]);
          if (s != servos_.end())
            writeTable(s->second, address, std::span(prm).subspan(at + 1, length));
        }
        break;
      }
      case dxl::inst::kSyncRead: {
        if (prm.size() < 4) break;
        const std::uint16_t address = u16(0), length = u16(2);
        for (std::size_t at = 4; at < prm.size(); ++at) {
          auto s = servos_.find(prm[at]);
          if (s != servos_.end())
            replies.push_back(dxl::statusPacket(prm[at], 0, readTable(s->second, address, length)));
        }
        break;
      }
      default:
        if (mine) replies.push_back(dxl::statusPacket(p.id, 2, {}));  // instruction error
        break;
    }
  }
  for (auto& r : replies)
    reply(std::move(r));
}

void SimDynamixelBus::run() {
  std::vector<std::uint8_t> rx;
  auto last = std::chrono::steady_clock::now();
  while (!stop_) {
    const auto in = pty_.read(512, std::chrono::milliseconds(5));
    const auto now = std::chrono::steady_clock::now();
    {
      std::lock_guard lock(mutex_);
      advance(std::chrono::duration<double>(now - last).count());
    }
    last = now;
    rx.insert(rx.end(), in.begin(), in.end());
    while (true) {
      const dxl::ParseResult r = dxl::parsePacket(rx);
      rx.erase(rx.begin(), rx.begin() + static_cast<std::ptrdiff_t>(r.consumed));
      if (r.outcome == dxl::ParseOutcome::kNeedMore) break;
      if (r.outcome == dxl::ParseOutcome::kCorrupt) {
        ++corruptIn_;
        continue;
      }
      ++packets_;
      handle(r.packet);
    }
    if (!pty_.masterOpen()) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

}  // namespace horopter::hw
