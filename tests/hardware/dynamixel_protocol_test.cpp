// DYNAMIXEL Protocol 2.0 against the ROBOTIS e-manual's own example packets
// (https://emanual.robotis.com/docs/en/dxl/protocol2/, sections "Ping",
// "Read", "Write", "Sync Read", "Sync Write": instruction and status packet
// examples), plus malformed, short, stuffed and corrupt input.
#include <gtest/gtest.h>

#include <numbers>
#include <sstream>

#include "horopter/core/error.hpp"
#include "horopter/hardware/dynamixel_protocol.hpp"

namespace dxl = horopter::hw::dxl;
using Bytes = std::vector<std::uint8_t>;

namespace {

Bytes hex(const std::string& text) {
  Bytes out;
  std::istringstream in(text);
  std::string b;
  while (in >> b)
    out.push_back(static_cast<std::uint8_t>(std::stoul(b, nullptr, 16)));
  return out;
}

dxl::Status statusOf(const Bytes& wire) {
  const auto r = dxl::parsePacket(wire);
  EXPECT_EQ(r.outcome, dxl::ParseOutcome::kPacket) << r.error;
  EXPECT_EQ(r.consumed, wire.size());
  return dxl::toStatus(r.packet);
}

}  // namespace

// e-manual "Ping" example: instruction to ID 1, status of an XM430-W210 (model 1030, firmware 38).
TEST(DynamixelProtocol, PingMatchesManual) {
  EXPECT_EQ(dxl::pingPacket(1), hex("FF FF FD 00 01 03 00 01 19 4E"));
  const auto s = statusOf(hex("FF FF FD 00 01 07 00 55 00 06 04 26 65 5D"));
  EXPECT_EQ(s.id, 1);
  EXPECT_EQ(s.error, 0);
  ASSERT_EQ(s.data.size(), 3u);
  EXPECT_EQ(dxl::fromLittleEndian(std::span(s.data).first(2)), 1030);
  EXPECT_EQ(s.data[2], 0x26);
}

// e-manual "Read" example: Present Position (132, 4 bytes) of ID 1, answer 166.
TEST(DynamixelProtocol, ReadMatchesManual) {
  EXPECT_EQ(dxl::readPacket(1, 132, 4), hex("FF FF FD 00 01 07 00 02 84 00 04 00 1D 15"));
  const auto s = statusOf(hex("FF FF FD 00 01 08 00 55 00 A6 00 00 00 8C C0"));
  EXPECT_EQ(dxl::fromLittleEndian(s.data), 166);
}

// e-manual "Write" example: Goal Position (116) = 512 to ID 1, and its status.
TEST(DynamixelProtocol, WriteMatchesManual) {
  const Bytes value = dxl::littleEndian(512, 4);
  EXPECT_EQ(dxl::writePacket(1, 116, value),
            hex("FF FF FD 00 01 09 00 03 74 00 00 02 00 00 CA 89"));
  const auto s = statusOf(hex("FF FF FD 00 01 04 00 55 00 A1 0C"));
  EXPECT_EQ(s.error, 0);
  EXPECT_TRUE(s.data.empty());
}

// e-manual "Sync Write" example: Goal Position 150 to ID 1 and 170 to ID 2.
TEST(DynamixelProtocol, SyncWriteMatchesManual) {
  EXPECT_EQ(dxl::syncWritePacket(116, 4, {{1, 150}, {2, 170}}),
            hex("FF FF FD 00 FE 11 00 83 74 00 04 00 01 96 00 00 00 02 AA 00 00 00 82 87"));
}

// e-manual "Sync Read" example: Present Position of IDs 1 and 2, answers 166 and 2079.
TEST(DynamixelProtocol, SyncReadMatchesManual) {
  EXPECT_EQ(dxl::syncReadPacket(132, 4, {1, 2}),
            hex("FF FF FD 00 FE 09 00 82 84 00 04 00 01 02 CE FA"));
  Bytes both = hex("FF FF FD 00 01 08 00 55 00 A6 00 00 00 8C C0");
  const Bytes second = hex("FF FF FD 00 02 08 00 55 00 1F 08 00 00 BA BE");
  both.insert(both.end(), second.begin(), second.end());
  const auto r1 = dxl::parsePacket(both);
  ASSERT_EQ(r1.outcome, dxl::ParseOutcome::kPacket);
  const auto r2 = dxl::parsePacket(std::span(both).subspan(r1.consumed));
  ASSERT_EQ(r2.outcome, dxl::ParseOutcome::kPacket);
  EXPECT_EQ(dxl::fromLittleEndian(dxl::toStatus(r1.packet).data), 166);
  EXPECT_EQ(dxl::toStatus(r2.packet).id, 2);
  EXPECT_EQ(dxl::fromLittleEndian(dxl::toStatus(r2.packet).data), 2079);
}

TEST(DynamixelProtocol, CrcOfManualPingIsItsTrailer) {
  const Bytes body = hex("FF FF FD 00 01 03 00 01");
  EXPECT_EQ(dxl::crc16(body), 0x4E19);
}

TEST(DynamixelProtocol, ByteStuffingRoundTripsAndCountsInLength) {
  const Bytes params = {0xFF, 0xFF, 0xFD, 0x01};
  const Bytes wire = dxl::encodePacket(3, dxl::inst::kWrite, params);
  // INST FF FF FD [FD] 01 -> 6 bytes + 2 CRC
  EXPECT_EQ(wire[5] | (wire[6] << 8), 8);
  EXPECT_EQ(wire[10], 0xFD);
  EXPECT_EQ(wire[11], 0xFD);  // the stuffed byte
  EXPECT_EQ(wire[12], 0x01);
  const auto r = dxl::parsePacket(wire);
  ASSERT_EQ(r.outcome, dxl::ParseOutcome::kPacket) << r.error;
  EXPECT_EQ(r.packet.params, params);
}

TEST(DynamixelProtocol, CorruptCrcIsReportedNotAccepted) {
  Bytes wire = hex("FF FF FD 00 01 08 00 55 00 A6 00 00 00 8C C0");
  wire.back() ^= 0x01;
  const auto r = dxl::parsePacket(wire);
  EXPECT_EQ(r.outcome, dxl::ParseOutcome::kCorrupt);
  EXPECT_NE(r.error.find("CRC"), std::string::npos);
  EXPECT_GT(r.consumed, 0u);
}

TEST(DynamixelProtocol, ShortFrameWaitsForMore) {
  const Bytes wire = hex("FF FF FD 00 01 08 00 55 00 A6");
  const auto r = dxl::parsePacket(wire);
  EXPECT_EQ(r.outcome, dxl::ParseOutcome::kNeedMore);
  EXPECT_EQ(r.consumed, 0u);
}

TEST(DynamixelProtocol, GarbageBeforeAPacketIsSkipped) {
  Bytes wire = {0x00, 0x13, 0xFF, 0x37, 0xFD};
  const Bytes good = hex("FF FF FD 00 01 04 00 55 00 A1 0C");
  wire.insert(wire.end(), good.begin(), good.end());
  const auto r = dxl::parsePacket(wire);
  ASSERT_EQ(r.outcome, dxl::ParseOutcome::kPacket);
  EXPECT_EQ(r.consumed, wire.size());
}

TEST(DynamixelProtocol, PureGarbageIsDroppedButAPartialHeaderKept) {
  const Bytes wire = {0x12, 0x34, 0x56, 0xFF, 0xFF};
  const auto r = dxl::parsePacket(wire);
  EXPECT_EQ(r.outcome, dxl::ParseOutcome::kNeedMore);
  EXPECT_EQ(r.consumed, 3u);
}

TEST(DynamixelProtocol, ImpossibleLengthIsCorrupt) {
  const Bytes wire = hex("FF FF FD 00 01 01 00 55");  // LEN 1 < 3
  EXPECT_EQ(dxl::parsePacket(wire).outcome, dxl::ParseOutcome::kCorrupt);
  const Bytes huge = hex("FF FF FD 00 01 FF FF 55");
  EXPECT_EQ(dxl::parsePacket(huge).outcome, dxl::ParseOutcome::kCorrupt);
}

TEST(DynamixelProtocol, StatusErrorsAreNamed) {
  EXPECT_EQ(dxl::describeError(0x03), "CRC error");
  EXPECT_NE(dxl::describeError(0x84).find("hardware alert"), std::string::npos);
  dxl::Packet notStatus;
  notStatus.instruction = dxl::inst::kPing;
  EXPECT_THROW(dxl::toStatus(notStatus), horopter::Error);
}

TEST(DynamixelProtocol, TicksAndRadiansForTheXSeries) {
  const dxl::ServoModel x;
  EXPECT_EQ(dxl::radiansToTicks(0, x), 2048);
  EXPECT_EQ(dxl::radiansToTicks(std::numbers::pi, x), 4096);
  EXPECT_NEAR(dxl::ticksToRadians(1024, x), -std::numbers::pi / 2, 1e-12);
  // 0.229 rpm per unit: 1 rad/s = 9.549 rpm = 41.7 -> 42 units
  EXPECT_EQ(dxl::radPerSecondToVelocityUnits(1.0, x), 42);
  EXPECT_EQ(dxl::radPerSecondToVelocityUnits(0.0, x), 1);
}

TEST(DynamixelProtocol, StatusWithoutErrorByteIsNotAStatus) {
  // A valid CRC around instruction 0x55 with no parameters: well-formed bytes, no ERROR byte.
  const dxl::ParseResult r = dxl::parsePacket(dxl::encodePacket(1, dxl::inst::kStatus, Bytes{}));
  ASSERT_EQ(r.outcome, dxl::ParseOutcome::kPacket);
  EXPECT_THROW(dxl::toStatus(r.packet), horopter::Error);
}

TEST(DynamixelProtocol, PositionTicksOutsideOneTurnAreNotPositions) {
  const dxl::ServoModel x;  // Position Control Mode: 0 .. 4095
  EXPECT_TRUE(dxl::isPositionTick(0, x));
  EXPECT_TRUE(dxl::isPositionTick(4095, x));
  EXPECT_FALSE(dxl::isPositionTick(-1, x));
  EXPECT_FALSE(dxl::isPositionTick(4096, x));
  EXPECT_FALSE(dxl::isPositionTick(0x7FFFFFFF, x));
  EXPECT_FALSE(dxl::isPositionTick(-0x7FFFFFFF - 1, x));
}
