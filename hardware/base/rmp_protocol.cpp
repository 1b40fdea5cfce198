// Segway RMP CAN frames and USB framing: see include/horopter/hardware/rmp_protocol.hpp.
#include "horopter/hardware/rmp_protocol.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "horopter/core/error.hpp"

namespace horopter::hw::rmp {

namespace {

constexpr double kDegPerRad = 180.0 / std::numbers::pi;

std::int16_t clampCounts(double counts) {
  const double r = std::round(counts);
  return static_cast<std::int16_t>(std::clamp(r, -32768.0, 32767.0));
}

void putI16(CanFrame& f, int at, std::int32_t v) {
  const auto u = static_cast<std::uint16_t>(static_cast<std::int16_t>(v));
  f.data[at] = static_cast<std::uint8_t>(u >> 8);
  f.data[at + 1] = static_cast<std::uint8_t>(u & 0xFF);
}
void putU16(CanFrame& f, int at, std::uint32_t v) {
  f.data[at] = static_cast<std::uint8_t>((v >> 8) & 0xFF);
  f.data[at + 1] = static_cast<std::uint8_t>(v & 0xFF);
}
// Low 16-bit word first, each word big-endian (libsegwayrmp getInt()).
void putI32(CanFrame& f, int at, std::int32_t v) {
  const auto u = static_cast<std::uint32_t>(v);
  putU16(f, at, u & 0xFFFF);
  putU16(f, at + 2, u >> 16);
}
std::int16_t getI16(const CanFrame& f, int at) {
  return static_cast<std::int16_t>((f.data[at] << 8) | f.data[at + 1]);
}
std::uint16_t getU16(const CanFrame& f, int at) {
  return static_cast<std::uint16_t>((f.data[at] << 8) | f.data[at + 1]);
}
std::int32_t getI32(const CanFrame& f, int at) {
  const std::uint32_t low = getU16(f, at);
  const std::uint32_t high = getU16(f, at + 2);
  return static_cast<std::int32_t>(low | (high << 16));
}
std::string hexId(std::uint32_t id) {
  char text[16];
  std::snprintf(text, sizeof text, "0x%03X", static_cast<unsigned>(id));
  return text;
}

// Why a decoded status is not one an RMP sends ("" when it is): see
// rmp_protocol.hpp for the bounds.
std::string implausible(const Status& st) {
  auto over = [](double value, double bound) { return !(std::abs(value) <= bound); };
  const double maxAngle = std::numbers::pi, maxRate = kMaxPlausibleRate,
               maxSpeed = kMaxPlausibleSpeed;
  if (over(st.pitch, maxAngle) || over(st.roll, maxAngle))
    return "pitch or roll beyond 180 degrees";
  if (over(st.pitchRate, maxRate) || over(st.rollRate, maxRate) || over(st.yawRate, maxRate))
    return "a turn rate beyond 1000 degrees/s";
  if (over(st.leftWheelSpeed, maxSpeed) || over(st.rightWheelSpeed, maxSpeed) ||
      over(st.commandedVelocity, maxSpeed))
    return "a speed beyond " + std::to_string(static_cast<int>(maxSpeed)) + " m/s";
  if (st.operationalMode < 0 || st.operationalMode > 3)
    return "operational mode " + std::to_string(st.operationalMode) + " (0..3 exist)";
  if (st.gainSchedule < 0 || st.gainSchedule > 2)
    return "gain schedule " + std::to_string(st.gainSchedule) + " (0..2 exist)";
  return {};
}

std::int32_t roundI32(double v) {
  return static_cast<std::int32_t>(std::clamp(std::round(v), -2147483648.0, 2147483647.0));
}

}  // namespace

Scaling scalingRmp200() {
  return {"rmp200", 332.0, 7.8, 33215.0, 112644.0, 1094.0};
}
Scaling scalingRmp100() {
  return {"rmp100", 401.0, 7.8, 40181.0, 117031.0, 1463.0};
}

Scaling scalingByName(const std::string& name) {
  if (name == "rmp200" || name == "rmp400") return scalingRmp200();
  if (name == "rmp100" || name == "rmp50") return scalingRmp100();
  throw Error("unknown RMP model '" + name + "': use rmp50, rmp100, rmp200 or rmp400");
}

CanFrame encodeMotion(const BaseVelocity& velocity, const Scaling& scaling) {
  CanFrame f;
  f.id = kCommandId;
  f.length = 8;
  putI16(f, 0, clampCounts(velocity.linear * scaling.countsPerMps));
  putI16(f, 2, clampCounts(velocity.angular * kDegPerRad * scaling.countsPerDegPerS));
  return f;
}

CanFrame encodeConfig(ConfigCommand command, std::uint16_t parameter) {
  CanFrame f;
  f.id = kCommandId;
  f.length = 8;
  putU16(f, 4, static_cast<std::uint16_t>(command));
  putU16(f, 6, parameter);
  return f;
}

MotionCounts decodeMotion(const CanFrame& frame) {
  if (frame.id != kCommandId || frame.length != 8)
    throw Error("not an RMP motion command (id 0x413, 8 bytes)");
  MotionCounts c;
  c.velocity = getI16(frame, 0);
  c.yawRate = getI16(frame, 2);
  c.configCommand = getU16(frame, 4);
  c.configParameter = getU16(frame, 6);
  return c;
}

BaseVelocity countsToVelocity(const MotionCounts& counts, const Scaling& scaling) {
  return {counts.velocity / scaling.countsPerMps,
          counts.yawRate / scaling.countsPerDegPerS / kDegPerRad};
}

bool decodeStatusFrame(const CanFrame& frame, const Scaling& s, Status& status) {
  if (frame.id < kStatusFirstId || frame.id > kStatusLastId) return false;
  if (frame.length > 8 || (frame.id != kStatusFirstId && frame.length != 8))
    throw Error("RMP status frame " + hexId(frame.id) + " has " + std::to_string(frame.length) +
                " data bytes, expected 8");
  Status st = status;  // written back only when every value is plausible
  const double degToRad = 1.0 / kDegPerRad;
  switch (frame.id) {
    case 0x401:
      st.pitch = getI16(frame, 0) / s.countsPerDegPerS * degToRad;
      st.pitchRate = getI16(frame, 2) / s.countsPerDegPerS * degToRad;
      st.roll = getI16(frame, 4) / s.countsPerDegPerS * degToRad;
      st.rollRate = getI16(frame, 6) / s.countsPerDegPerS * degToRad;
      break;
    case 0x402:
      st.leftWheelSpeed = getI16(frame, 0) / s.countsPerMps;
      st.rightWheelSpeed = getI16(frame, 2) / s.countsPerMps;
      st.yawRate = getI16(frame, 4) / s.countsPerDegPerS * degToRad;
      st.servoFrames = getU16(frame, 6) * 0.01;
      break;
    case 0x403:
      st.leftWheelDisplacement = getI32(frame, 0) / s.countsPerMetre;
      st.rightWheelDisplacement = getI32(frame, 4) / s.countsPerMetre;
      break;
    case 0x404:
      st.foreAftDisplacement = getI32(frame, 0) / s.countsPerMetre;
      st.yawDisplacement = getI32(frame, 4) / s.countsPerRev * 2.0 * std::numbers::pi;
      break;
    case 0x405:
      st.leftMotorTorque = getI16(frame, 0) / s.countsPerNm;
      st.rightMotorTorque = getI16(frame, 2) / s.countsPerNm;
      break;
    case 0x406:
      st.operationalMode = getI16(frame, 0);
      st.gainSchedule = getI16(frame, 2);
      st.uiBatteryVolts = getU16(frame, 4) * 0.0125 + 1.4;
      st.powerbaseBatteryVolts = getU16(frame, 6) / 4.0;
      break;
    case 0x407:
      st.commandedVelocity = getI16(frame, 0) / s.countsPerMps;
      st.commandedYawRateCounts = getI16(frame, 2);
      break;
    default:
      break;
  }
  const std::string bad = implausible(st);
  if (!bad.empty()) throw Error("RMP status frame " + hexId(frame.id) + ": " + bad);
  st.receivedMask |= 1u << (frame.id - kStatusFirstId);
  status = st;
  return true;
}

std::optional<bool> decodeMotorStatus(const CanFrame& frame) {
  if (frame.id != kMotorStatusId || frame.length < 4) return std::nullopt;
  return frame.data[3] == 0x80;
}

CanFrame encodeMotorStatus(bool motorsEnabled) {
  CanFrame f;
  f.id = kMotorStatusId;
  f.length = 8;
  f.data[3] = motorsEnabled ? 0x80 : 0x00;
  return f;
}

std::array<CanFrame, 8> encodeStatusFrames(const Status& st, const Scaling& s) {
  std::array<CanFrame, 8> frames{};
  for (std::uint32_t i = 0; i < 8; ++i) {
    frames[i].id = kStatusFirstId + i;
    frames[i].length = 8;
  }
  const double toDeg = kDegPerRad;
  putI16(frames[1], 0, clampCounts(st.pitch * toDeg * s.countsPerDegPerS));
  putI16(frames[1], 2, clampCounts(st.pitchRate * toDeg * s.countsPerDegPerS));
  putI16(frames[1], 4, clampCounts(st.roll * toDeg * s.countsPerDegPerS));
  putI16(frames[1], 6, clampCounts(st.rollRate * toDeg * s.countsPerDegPerS));
  putI16(frames[2], 0, clampCounts(st.leftWheelSpeed * s.countsPerMps));
  putI16(frames[2], 2, clampCounts(st.rightWheelSpeed * s.countsPerMps));
  putI16(frames[2], 4, clampCounts(st.yawRate * toDeg * s.countsPerDegPerS));
  putU16(frames[2], 6, static_cast<std::uint32_t>(std::lround(st.servoFrames * 100.0)) & 0xFFFF);
  putI32(frames[3], 0, roundI32(st.leftWheelDisplacement * s.countsPerMetre));
  putI32(frames[3], 4, roundI32(st.rightWheelDisplacement * s.countsPerMetre));
  putI32(frames[4], 0, roundI32(st.foreAftDisplacement * s.countsPerMetre));
  putI32(frames[4], 4, roundI32(st.yawDisplacement / (2.0 * std::numbers::pi) * s.countsPerRev));
  putI16(frames[5], 0, clampCounts(st.leftMotorTorque * s.countsPerNm));
  putI16(frames[5], 2, clampCounts(st.rightMotorTorque * s.countsPerNm));
  putI16(frames[6], 0, st.operationalMode);
  putI16(frames[6], 2, st.gainSchedule);
  putU16(frames[6], 4,
         static_cast<std::uint32_t>(std::max(0L, std::lround((st.uiBatteryVolts - 1.4) / 0.0125))));
  putU16(frames[6], 6,
         static_cast<std::uint32_t>(std::max(0L, std::lround(st.powerbaseBatteryVolts * 4.0))));
  putI16(frames[7], 0, clampCounts(st.commandedVelocity * s.countsPerMps));
  putI16(frames[7], 2, st.commandedYawRateCounts);
  return frames;
}

std::uint8_t usbChecksum(std::span<const std::uint8_t> first17) {
  std::uint32_t sum = 0;
  for (std::size_t i = 0; i < 17 && i < first17.size(); ++i)
    sum += first17[i];
  sum = (sum & 0xFF) + (sum >> 8);
  sum = (sum & 0xFF) + (sum >> 8);
  return static_cast<std::uint8_t>((~sum + 1) & 0xFF);
}

std::array<std::uint8_t, kUsbFrameSize> encodeUsbToRmp(const CanFrame& frame,
                                                       std::uint8_t channel) {
  std::array<std::uint8_t, kUsbFrameSize> p{};
  p[0] = 0xF0;
  p[1] = 0x55;
  p[2] = channel;
  p[6] = static_cast<std::uint8_t>((frame.id >> 8) & 0xFF);
  p[7] = static_cast<std::uint8_t>(frame.id & 0xFF);
  for (int i = 0; i < 8; ++i)
    p[9 + i] = frame.data[i];
  p[17] = usbChecksum(p);
  return p;
}

std::array<std::uint8_t, kUsbFrameSize> encodeUsbFromRmp(const CanFrame& frame,
                                                         std::uint8_t channel) {
  std::array<std::uint8_t, kUsbFrameSize> p{};
  p[0] = 0xF0;
  p[1] = 0x55;
  p[2] = channel;
  p[4] = static_cast<std::uint8_t>((frame.id >> 3) & 0xFF);
  p[5] = static_cast<std::uint8_t>((frame.id & 0x7) << 5);
  for (int i = 0; i < 8; ++i)
    p[9 + i] = frame.data[i];
  p[17] = usbChecksum(p);
  return p;
}

namespace {

// The first frame in `buffer` whose header is F0 55 and a channel byte that
// `channelOk` accepts; `decodeId` reads the identifier from the packet (the
// two directions place it differently).
template <class ChannelOk, class DecodeId>
UsbParse parseUsb(std::span<const std::uint8_t> buffer, ChannelOk channelOk, DecodeId decodeId) {
  UsbParse r;
  std::size_t start = 0;
  while (start < buffer.size()) {
    if (buffer[start] != 0xF0) {
      ++start;
      continue;
    }
    if (start + 1 < buffer.size() && buffer[start + 1] != 0x55) {
      ++start;
      continue;
    }
    if (start + 2 < buffer.size() && !channelOk(buffer[start + 2])) {
      ++start;
      continue;
    }
    break;
  }
  if (buffer.size() - start < kUsbFrameSize) {
    r.outcome = UsbOutcome::kNeedMore;
    r.consumed = start;
    return r;
  }
  const auto p = buffer.subspan(start, kUsbFrameSize);
  if (usbChecksum(p) != p[17]) {
    r.outcome = UsbOutcome::kCorrupt;
    r.consumed = start + 1;
    r.error = "RMP USB frame checksum mismatch";
    return r;
  }
  r.outcome = UsbOutcome::kFrame;
  r.consumed = start + kUsbFrameSize;
  r.channel = p[2];
  r.frame.id = decodeId(p) & 0x7FF;
  r.frame.length = 8;
  for (int i = 0; i < 8; ++i)
    r.frame.data[i] = p[9 + i];
  return r;
}

}  // namespace

UsbParse parseUsbFromRmp(std::span<const std::uint8_t> buffer) {
  return parseUsb(
      buffer, [](std::uint8_t c) { return c == 0xAA || c == 0xBB; },
      [](std::span<const std::uint8_t> p) {
        return (static_cast<std::uint32_t>(p[4]) << 3) | ((p[5] >> 5) & 7);
      });
}

UsbParse parseUsbToRmp(std::span<const std::uint8_t> buffer) {
  return parseUsb(
      buffer, [](std::uint8_t c) { return c == 0x00 || c == 0x01; },
      [](std::span<const std::uint8_t> p) {
        return (static_cast<std::uint32_t>(p[6]) << 8) | p[7];
      });
}

}  // namespace horopter::hw::rmp
