// DYNAMIXEL Protocol 2.0: instruction and status packets, pure functions.
//
// Source: ROBOTIS e-manual, "DYNAMIXEL Protocol 2.0"
// (https://emanual.robotis.com/docs/en/dxl/protocol2/), and the X-series
// control tables (e.g. https://emanual.robotis.com/docs/en/dxl/x/xm430-w350/).
//
//   Packet   FF FF FD 00 | ID | LEN_L LEN_H | INST | PARAM... | CRC_L CRC_H
//   LEN      number of bytes after LEN: INST + PARAMs (after stuffing) + 2 (CRC)
//   Status   INST = 0x55, first parameter = ERROR (bit 7: hardware alert,
//            bits 0-6: 1 result fail, 2 instruction error, 3 CRC error,
//            4 data range, 5 data length, 6 data limit, 7 access error)
//   CRC      CRC-16, polynomial 0x8005 (x^16+x^15+x^2+1), initial value 0, no
//            reflection, over every byte from the header to the last
//            parameter; sent little-endian
//   Stuffing FF FF FD inside INST..PARAMs is sent as FF FF FD FD
//   Multi-byte values are little-endian. ID 0xFE is broadcast.
//
// Golden vectors from the e-manual's examples are in
// tests/hardware/dynamixel_protocol_test.cpp.
#pragma once

#include "horopter/core/export.hpp"

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace horopter::hw::dxl {

constexpr std::uint8_t kBroadcastId = 0xFE;

namespace inst {
constexpr std::uint8_t kPing = 0x01;
constexpr std::uint8_t kRead = 0x02;
constexpr std::uint8_t kWrite = 0x03;
constexpr std::uint8_t kStatus = 0x55;
constexpr std::uint8_t kSyncRead = 0x82;
constexpr std::uint8_t kSyncWrite = 0x83;
constexpr std::uint8_t kBulkRead = 0x92;
}  // namespace inst

// One decoded packet (instruction or status), parameters unstuffed.
struct HOROPTER_API Packet {
  std::uint8_t id = 0;
  std::uint8_t instruction = 0;
  std::vector<std::uint8_t> params;
};

// A status packet's fields: the ERROR byte split off the parameters.
struct HOROPTER_API Status {
  std::uint8_t id = 0;
  std::uint8_t error = 0;
  std::vector<std::uint8_t> data;
};

HOROPTER_API std::uint16_t crc16(std::span<const std::uint8_t> bytes);

// A complete packet on the wire (stuffing applied, CRC appended).
HOROPTER_API std::vector<std::uint8_t> encodePacket(std::uint8_t id, std::uint8_t instruction,
                                                    std::span<const std::uint8_t> params);
inline std::vector<std::uint8_t> encodePacket(std::uint8_t id, std::uint8_t instruction,
                                              const std::vector<std::uint8_t>& params) {
  return encodePacket(id, instruction, std::span<const std::uint8_t>(params));
}

enum class ParseOutcome {
  kPacket,    // `packet` holds a valid packet; `consumed` bytes used
  kNeedMore,  // a packet may start here but is incomplete; `consumed` garbage bytes may go
  kCorrupt,   // bad length or CRC: drop `consumed` bytes and look again; `error` says why
};

struct HOROPTER_API ParseResult {
  ParseOutcome outcome = ParseOutcome::kNeedMore;
  Packet packet;
  std::size_t consumed = 0;
  std::string error;
};

// Finds the first packet in `buffer` (bytes before a header are skipped and
// counted in `consumed`). Never throws; malformed input gives kCorrupt.
HOROPTER_API ParseResult parsePacket(std::span<const std::uint8_t> buffer);

// Instruction builders (the whole packet on the wire).
HOROPTER_API std::vector<std::uint8_t> pingPacket(std::uint8_t id);
HOROPTER_API std::vector<std::uint8_t> readPacket(std::uint8_t id, std::uint16_t address,
                                                  std::uint16_t length);
HOROPTER_API std::vector<std::uint8_t> writePacket(std::uint8_t id, std::uint16_t address,
                                                   std::span<const std::uint8_t> data);
// Sync write of one `length`-byte item to several servos: {id, value} pairs,
// values little-endian in `length` bytes.
HOROPTER_API std::vector<std::uint8_t> syncWritePacket(
    std::uint16_t address, std::uint16_t length,
    const std::vector<std::pair<std::uint8_t, std::int32_t>>& values);
HOROPTER_API std::vector<std::uint8_t> syncReadPacket(std::uint16_t address, std::uint16_t length,
                                                      const std::vector<std::uint8_t>& ids);
HOROPTER_API std::vector<std::uint8_t> statusPacket(std::uint8_t id, std::uint8_t error,
                                                    std::span<const std::uint8_t> data);

// The status fields of a packet; throws horopter::Error if it is not a status packet.
HOROPTER_API Status toStatus(const Packet& packet);
// "CRC error", "data range error", ... for a status ERROR byte.
HOROPTER_API std::string describeError(std::uint8_t error);

HOROPTER_API std::vector<std::uint8_t> littleEndian(std::int32_t value, std::size_t bytes);
HOROPTER_API std::int32_t fromLittleEndian(std::span<const std::uint8_t> bytes);

// The control-table facts a driver needs for one servo family.
struct HOROPTER_API ServoModel {
  std::string family = "X series (XM430/XL430/XH430)";
  int ticksPerTurn = 4096;                     // position resolution
  int centreTick = 2048;                       // 0 rad
  std::uint16_t velocityLimitAddress = 44;     // 4 bytes, unit velocityUnitRpm (EEPROM)
  std::uint16_t maxPositionLimitAddress = 48;  // 4 bytes (EEPROM)
  std::uint16_t minPositionLimitAddress = 52;  // 4 bytes (EEPROM)
  std::uint16_t torqueEnableAddress = 64;
  std::uint16_t profileVelocityAddress = 112;  // 4 bytes, unit velocityUnitRpm
  std::uint16_t goalPositionAddress = 116;     // 4 bytes
  std::uint16_t presentVelocityAddress = 128;  // 4 bytes
  std::uint16_t presentPositionAddress = 132;  // 4 bytes
  double velocityUnitRpm = 0.229;
  // Position Control Mode range of Goal/Present Position and of the position
  // limits (one turn); the multi-turn modes are not used by the head.
  std::int32_t minPositionTick = 0;
  std::int32_t maxPositionTick = 4095;
  std::int32_t maxVelocityLimit = 1023;  // Velocity Limit (44) range 0 .. 1023
};

// True for ticks within the model's Position Control Mode range: anything else
// (0x7FFFFFFF, -1) is not a position this servo reports, never an angle.
HOROPTER_API bool isPositionTick(std::int32_t ticks, const ServoModel& model);
HOROPTER_API double ticksToRadians(std::int32_t ticks, const ServoModel& model);
HOROPTER_API std::int32_t radiansToTicks(double radians, const ServoModel& model);
// Profile Velocity units for a speed in rad/s (at least 1: 0 means "no limit").
HOROPTER_API std::int32_t radPerSecondToVelocityUnits(double radPerSecond, const ServoModel& model);
HOROPTER_API double velocityUnitsToRadPerSecond(std::int32_t units, const ServoModel& model);

}  // namespace horopter::hw::dxl
