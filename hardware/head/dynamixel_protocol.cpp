// DYNAMIXEL Protocol 2.0 packets: see include/horopter/hardware/dynamixel_protocol.hpp.
#include "horopter/hardware/dynamixel_protocol.hpp"

#include <cmath>
#include <numbers>

#include "horopter/core/error.hpp"

namespace horopter::hw::dxl {

namespace {

constexpr std::uint8_t kHeader[4] = {0xFF, 0xFF, 0xFD, 0x00};
// Longest packet we accept; a bigger LEN is corruption, not a packet to wait for.
constexpr std::size_t kMaxLength = 1024;

std::vector<std::uint8_t> stuff(std::span<const std::uint8_t> in) {
  std::vector<std::uint8_t> out;
  out.reserve(in.size() + 4);
  for (std::size_t i = 0; i < in.size(); ++i) {
    out.push_back(in[i]);
    if (i >= 2 && in[i] == 0xFD && in[i - 1] == 0xFF && in[i - 2] == 0xFF) out.push_back(0xFD);
  }
  return out;
}

std::vector<std::uint8_t> unstuff(std::span<const std::uint8_t> in) {
  std::vector<std::uint8_t> out;
  out.reserve(in.size());
  for (std::size_t i = 0; i < in.size(); ++i) {
    out.push_back(in[i]);
    if (i >= 2 && in[i] == 0xFD && in[i - 1] == 0xFF && in[i - 2] == 0xFF && i + 1 < in.size() &&
        in[i + 1] == 0xFD)
      ++i;  // skip the stuffed FD
  }
  return out;
}

void putU16(std::vector<std::uint8_t>& v, std::uint16_t x) {
  v.push_back(static_cast<std::uint8_t>(x & 0xFF));
  v.push_back(static_cast<std::uint8_t>(x >> 8));
}

}  // namespace

std::uint16_t crc16(std::span<const std::uint8_t> bytes) {
  std::uint16_t crc = 0;
  for (std::uint8_t b : bytes) {
    crc ^= static_cast<std::uint16_t>(b) << 8;
    for (int bit = 0; bit < 8; ++bit)
      crc = (crc & 0x8000) ? static_cast<std::uint16_t>((crc << 1) ^ 0x8005)
                           : static_cast<std::uint16_t>(crc << 1);
  }
  return crc;
}

std::vector<std::uint8_t> encodePacket(std::uint8_t id, std::uint8_t instruction,
                                       std::span<const std::uint8_t> params) {
  std::vector<std::uint8_t> body;
  body.reserve(params.size() + 1);
  body.push_back(instruction);
  body.insert(body.end(), params.begin(), params.end());
  const std::vector<std::uint8_t> stuffed = stuff(body);
  std::vector<std::uint8_t> out(std::begin(kHeader), std::end(kHeader));
  out.push_back(id);
  putU16(out, static_cast<std::uint16_t>(stuffed.size() + 2));
  out.insert(out.end(), stuffed.begin(), stuffed.end());
  putU16(out, crc16(out));
  return out;
}

ParseResult parsePacket(std::span<const std::uint8_t> buffer) {
  ParseResult r;
  // Find a header; everything before it is garbage.
  std::size_t start = 0;
  for (; start + 4 <= buffer.size(); ++start)
    if (buffer[start] == 0xFF && buffer[start + 1] == 0xFF && buffer[start + 2] == 0xFD &&
        buffer[start + 3] == 0x00)
      break;
  if (start + 4 > buffer.size()) {
    // Keep a possible partial header at the end.
    std::size_t keep = 0;
    for (std::size_t k = std::min<std::size_t>(3, buffer.size()); k > 0; --k) {
      if (std::equal(buffer.end() - static_cast<std::ptrdiff_t>(k), buffer.end(), kHeader)) {
        keep = k;
        break;
      }
    }
    r.outcome = ParseOutcome::kNeedMore;
    r.consumed = buffer.size() - keep;
    return r;
  }
  const std::span<const std::uint8_t> p = buffer.subspan(start);
  if (p.size() < 7) {
    r.outcome = ParseOutcome::kNeedMore;
    r.consumed = start;
    return r;
  }
  const std::size_t length = p[5] | (static_cast<std::size_t>(p[6]) << 8);
  if (length < 3 || length > kMaxLength) {
    r.outcome = ParseOutcome::kCorrupt;
    r.consumed = start + 4;
    r.error =
        "packet LEN " + std::to_string(length) + " out of range 3.." + std::to_string(kMaxLength);
    return r;
  }
  const std::size_t total = 7 + length;
  if (p.size() < total) {
    r.outcome = ParseOutcome::kNeedMore;
    r.consumed = start;
    return r;
  }
  const std::uint16_t expected = crc16(p.first(total - 2));
  const std::uint16_t got = static_cast<std::uint16_t>(p[total - 2] | (p[total - 1] << 8));
  if (expected != got) {
    r.outcome = ParseOutcome::kCorrupt;
    r.consumed = start + 4;
    r.error = "CRC mismatch (packet says " + std::to_string(got) + ", bytes give " +
              std::to_string(expected) + ")";
    return r;
  }
  const std::vector<std::uint8_t> body = unstuff(p.subspan(7, length - 2));
  r.outcome = ParseOutcome::kPacket;
  r.consumed = start + total;
  r.packet.id = p[4];
  r.packet.instruction = body[0];
  r.packet.params.assign(body.begin() + 1, body.end());
  return r;
}

std::vector<std::uint8_t> littleEndian(std::int32_t value, std::size_t bytes) {
  std::vector<std::uint8_t> out(bytes);
  const auto u = static_cast<std::uint32_t>(value);
  for (std::size_t i = 0; i < bytes; ++i)
    out[i] = static_cast<std::uint8_t>(u >> (8 * i));
  return out;
}

std::int32_t fromLittleEndian(std::span<const std::uint8_t> bytes) {
  std::uint32_t u = 0;
  for (std::size_t i = 0; i < bytes.size() && i < 4; ++i)
    u |= static_cast<std::uint32_t>(bytes[i]) << (8 * i);
  if (bytes.size() == 2) return static_cast<std::int16_t>(u);  // sign of a 2-byte item
  return static_cast<std::int32_t>(u);
}

std::vector<std::uint8_t> pingPacket(std::uint8_t id) {
  return encodePacket(id, inst::kPing, std::span<const std::uint8_t>());
}

std::vector<std::uint8_t> readPacket(std::uint8_t id, std::uint16_t address, std::uint16_t length) {
  std::vector<std::uint8_t> params;
  putU16(params, address);
  putU16(params, length);
  return encodePacket(id, inst::kRead, params);
}

std::vector<std::uint8_t> writePacket(std::uint8_t id, std::uint16_t address,
                                      std::span<const std::uint8_t> data) {
  std::vector<std::uint8_t> params;
  putU16(params, address);
  params.insert(params.end(), data.begin(), data.end());
  return encodePacket(id, inst::kWrite, params);
}

std::vector<std::uint8_t> syncWritePacket(
    std::uint16_t address, std::uint16_t length,
    const std::vector<std::pair<std::uint8_t, std::int32_t>>& values) {
  if (length == 0 || length > 4)
    throw Error("sync write item length must be 1..4 bytes, got " + std::to_string(length));
  std::vector<std::uint8_t> params;
  putU16(params, address);
  putU16(params, length);
  for (const auto& [id, value] : values) {
    params.push_back(id);
    const auto bytes = littleEndian(value, length);
    params.insert(params.end(), bytes.begin(), bytes.end());
  }
  return encodePacket(kBroadcastId, inst::kSyncWrite, params);
}

std::vector<std::uint8_t> syncReadPacket(std::uint16_t address, std::uint16_t length,
                                         const std::vector<std::uint8_t>& ids) {
  std::vector<std::uint8_t> params;
  putU16(params, address);
  putU16(params, length);
  params.insert(params.end(), ids.begin(), ids.end());
  return encodePacket(kBroadcastId, inst::kSyncRead, params);
}

std::vector<std::uint8_t> statusPacket(std::uint8_t id, std::uint8_t error,
                                       std::span<const std::uint8_t> data) {
  std::vector<std::uint8_t> params;
  params.push_back(error);
  params.insert(params.end(), data.begin(), data.end());
  return encodePacket(id, inst::kStatus, params);
}

Status toStatus(const Packet& packet) {
  if (packet.instruction != inst::kStatus || packet.params.empty())
    throw Error("expected a status packet (instruction 0x55 with an ERROR byte), got instruction " +
                std::to_string(packet.instruction));
  Status s;
  s.id = packet.id;
  s.error = packet.params[0];
  s.data.assign(packet.params.begin() + 1, packet.params.end());
  return s;
}

std::string describeError(std::uint8_t error) {
  static const char* const kNames[] = {"no error",         "result fail",      "instruction error",
                                       "CRC error",        "data range error", "data length error",
                                       "data limit error", "access error"};
  const int code = error & 0x7F;
  std::string s = code < 8 ? kNames[code] : "unknown error " + std::to_string(code);
  if (error & 0x80) s += " (hardware alert: read Hardware Error Status)";
  return s;
}

bool isPositionTick(std::int32_t ticks, const ServoModel& model) {
  return ticks >= model.minPositionTick && ticks <= model.maxPositionTick;
}

double ticksToRadians(std::int32_t ticks, const ServoModel& model) {
  return (ticks - model.centreTick) * 2.0 * std::numbers::pi / model.ticksPerTurn;
}

std::int32_t radiansToTicks(double radians, const ServoModel& model) {
  return model.centreTick + static_cast<std::int32_t>(std::lround(radians * model.ticksPerTurn /
                                                                  (2.0 * std::numbers::pi)));
}

std::int32_t radPerSecondToVelocityUnits(double radPerSecond, const ServoModel& model) {
  const double rpm = std::abs(radPerSecond) * 60.0 / (2.0 * std::numbers::pi);
  return std::max<std::int32_t>(
      1, static_cast<std::int32_t>(std::lround(rpm / model.velocityUnitRpm)));
}

double velocityUnitsToRadPerSecond(std::int32_t units, const ServoModel& model) {
  return units * model.velocityUnitRpm * 2.0 * std::numbers::pi / 60.0;
}

}  // namespace horopter::hw::dxl
