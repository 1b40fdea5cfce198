// Segway RMP frames against the layout libsegwayrmp implements
// (src/segwayrmp.cc move()/ParsePacket_(), src/impl/rmp_io.cc sendPacket()/
// getPacket()/computeChecksum()). The expected bytes below are worked out by
// hand from that layout and the RMP 200 constants (332 counts per m/s, 7.8
// per deg/s, 33215 per m, 112644 per revolution); no captured RMP traffic
// was available.
#include <gtest/gtest.h>

#include <numbers>

#include "horopter/core/error.hpp"
#include "horopter/hardware/rmp_protocol.hpp"

namespace rmp = horopter::hw::rmp;
using horopter::hw::CanFrame;

TEST(RmpProtocol, MotionFrameScalingAndByteOrder) {
  // 0.5 m/s -> 166 counts (0x00A6); 10 deg/s -> 78 counts (0x004E); big-endian.
  const CanFrame f = rmp::encodeMotion({0.5, 10.0 * std::numbers::pi / 180}, rmp::scalingRmp200());
  EXPECT_EQ(f.id, 0x413u);
  EXPECT_EQ(f.length, 8);
  const std::array<std::uint8_t, 8> want = {0x00, 0xA6, 0x00, 0x4E, 0, 0, 0, 0};
  EXPECT_EQ(f.data, want);
  // Backwards: -1 m/s -> -332 = 0xFEB4.
  const CanFrame b = rmp::encodeMotion({-1.0, 0}, rmp::scalingRmp200());
  EXPECT_EQ(b.data[0], 0xFE);
  EXPECT_EQ(b.data[1], 0xB4);
  // RMP 100 uses 401 counts per m/s.
  EXPECT_EQ(rmp::decodeMotion(rmp::encodeMotion({1.0, 0}, rmp::scalingRmp100())).velocity, 401);
}

TEST(RmpProtocol, OutOfRangeCountsClampInsteadOfWrapping) {
  const auto c = rmp::decodeMotion(rmp::encodeMotion({1000.0, -1000.0}, rmp::scalingRmp200()));
  EXPECT_EQ(c.velocity, 32767);
  EXPECT_EQ(c.yawRate, -32768);
}

TEST(RmpProtocol, ConfigFrames) {
  const CanFrame f = rmp::encodeConfig(rmp::ConfigCommand::kOperationalMode, 1);
  const std::array<std::uint8_t, 8> want = {0, 0, 0, 0, 0x00, 0x10, 0x00, 0x01};
  EXPECT_EQ(f.data, want);
}

TEST(RmpProtocol, StatusFramesDecodeToSiUnits) {
  rmp::Status st;
  CanFrame f;
  f.length = 8;
  // 0x401 pitch 78 counts = 10 deg.
  f.id = 0x401;
  f.data = {0x00, 0x4E, 0xFF, 0xB2, 0, 0, 0, 0};
  ASSERT_TRUE(rmp::decodeStatusFrame(f, rmp::scalingRmp200(), st));
  EXPECT_NEAR(st.pitch, 10 * std::numbers::pi / 180, 1e-12);
  EXPECT_NEAR(st.pitchRate, -10 * std::numbers::pi / 180, 1e-12);
  // 0x402 left wheel 332 counts = 1 m/s, right -166 = -0.5 m/s, servo frames 250 * 0.01 s.
  f.id = 0x402;
  f.data = {0x01, 0x4C, 0xFF, 0x5A, 0x00, 0x00, 0x00, 0xFA};
  ASSERT_TRUE(rmp::decodeStatusFrame(f, rmp::scalingRmp200(), st));
  EXPECT_DOUBLE_EQ(st.leftWheelSpeed, 1.0);
  EXPECT_DOUBLE_EQ(st.rightWheelSpeed, -0.5);
  EXPECT_DOUBLE_EQ(st.servoFrames, 2.5);
  // 0x404 fore-aft 33215 counts = 1 m sent LOW word first: 0x000081BF -> 81 BF 00 00;
  // yaw 112644 counts = 1 revolution: 0x0001B804 -> B8 04 00 01.
  f.id = 0x404;
  f.data = {0x81, 0xBF, 0x00, 0x00, 0xB8, 0x04, 0x00, 0x01};
  ASSERT_TRUE(rmp::decodeStatusFrame(f, rmp::scalingRmp200(), st));
  EXPECT_DOUBLE_EQ(st.foreAftDisplacement, 1.0);
  EXPECT_NEAR(st.yawDisplacement, 2 * std::numbers::pi, 1e-12);
  // 0x406 mode 1 (tractor), battery words.
  f.id = 0x406;
  f.data = {0x00, 0x01, 0x00, 0x02, 0x01, 0xE0, 0x01, 0x20};
  ASSERT_TRUE(rmp::decodeStatusFrame(f, rmp::scalingRmp200(), st));
  EXPECT_EQ(st.operationalMode, 1);
  EXPECT_EQ(st.gainSchedule, 2);
  EXPECT_NEAR(st.uiBatteryVolts, 480 * 0.0125 + 1.4, 1e-12);
  EXPECT_DOUBLE_EQ(st.powerbaseBatteryVolts, 72.0);
  EXPECT_EQ(st.receivedMask, (1u << 1) | (1u << 2) | (1u << 4) | (1u << 6));
}

TEST(RmpProtocol, OtherTrafficIgnoredAndBadLengthsRejected) {
  rmp::Status st;
  CanFrame other;
  other.id = 0x680;
  EXPECT_FALSE(rmp::decodeStatusFrame(other, rmp::scalingRmp200(), st));
  CanFrame shortFrame;
  shortFrame.id = 0x403;
  shortFrame.length = 4;
  EXPECT_THROW(rmp::decodeStatusFrame(shortFrame, rmp::scalingRmp200(), st), horopter::Error);
}

// Values no RMP reports are rejected, and a rejected frame leaves the status as it was.
TEST(RmpProtocol, ImplausibleStatusValuesAreRejected) {
  const rmp::Scaling s = rmp::scalingRmp200();
  rmp::Status st;
  st.leftWheelSpeed = 0.25;
  st.operationalMode = 1;
  auto rejected = [&](std::uint32_t id, std::array<std::uint8_t, 8> data, std::uint8_t length = 8) {
    CanFrame f;
    f.id = id;
    f.length = length;
    f.data = data;
    const rmp::Status before = st;
    bool threw = false;
    try {
      rmp::decodeStatusFrame(f, s, st);
    } catch (const horopter::Error&) {
      threw = true;
    }
    EXPECT_EQ(st.leftWheelSpeed, before.leftWheelSpeed);
    EXPECT_EQ(st.operationalMode, before.operationalMode);
    EXPECT_EQ(st.receivedMask, before.receivedMask);
    return threw;
  };
  // 0x402 wheel speed 32767 counts = 98.7 m/s.
  EXPECT_TRUE(rejected(0x402, {0x7F, 0xFF, 0, 0, 0, 0, 0, 0}));
  // 0x401 pitch -32768 counts = -4201 deg.
  EXPECT_TRUE(rejected(0x401, {0x80, 0x00, 0, 0, 0, 0, 0, 0}));
  // 0x402 yaw rate 32767 counts = 4201 deg/s.
  EXPECT_TRUE(rejected(0x402, {0, 0, 0, 0, 0x7F, 0xFF, 0, 0}));
  // 0x406 operational mode 9 (0..3 exist), gain schedule -1 (0..2 exist).
  EXPECT_TRUE(rejected(0x406, {0x00, 0x09, 0, 0, 0, 0, 0, 0}));
  EXPECT_TRUE(rejected(0x406, {0x00, 0x01, 0xFF, 0xFF, 0, 0, 0, 0}));
  // 0x407 commanded velocity -32768 counts = -98.7 m/s.
  EXPECT_TRUE(rejected(0x407, {0x80, 0x00, 0, 0, 0, 0, 0, 0}));
  // Lengths: 9 data bytes on any status id (CAN has at most 8), 0 on 0x405.
  EXPECT_TRUE(rejected(0x400, {}, 9));
  EXPECT_TRUE(rejected(0x405, {}, 0));
  // The same frame with plausible values decodes.
  CanFrame ok;
  ok.id = 0x406;
  ok.data = {0x00, 0x02, 0x00, 0x01, 0, 0, 0, 0};
  ASSERT_TRUE(rmp::decodeStatusFrame(ok, s, st));
  EXPECT_EQ(st.operationalMode, 2);
}

TEST(RmpProtocol, StatusEncodeDecodeRoundTrip) {
  rmp::Status in;
  in.leftWheelSpeed = 0.3;
  in.rightWheelSpeed = 0.4;
  in.yawRate = -0.25;
  in.foreAftDisplacement = -12.5;
  in.yawDisplacement = 3.0;
  in.leftMotorTorque = 1.5;
  in.powerbaseBatteryVolts = 71.25;
  rmp::Status out;
  for (const CanFrame& f : rmp::encodeStatusFrames(in, rmp::scalingRmp200()))
    ASSERT_TRUE(rmp::decodeStatusFrame(f, rmp::scalingRmp200(), out));
  EXPECT_EQ(out.receivedMask, 0xFFu);
  EXPECT_NEAR(out.leftWheelSpeed, 0.3, 1.0 / 332);
  EXPECT_NEAR(out.yawRate, -0.25, 1e-2);
  EXPECT_NEAR(out.foreAftDisplacement, -12.5, 1.0 / 33215);
  EXPECT_NEAR(out.yawDisplacement, 3.0, 1e-4);
  EXPECT_NEAR(out.leftMotorTorque, 1.5, 1.0 / 1094);
  EXPECT_DOUBLE_EQ(out.powerbaseBatteryVolts, 71.25);
}

TEST(RmpProtocol, UsbPacketToRmpLayoutAndChecksum) {
  // 0.5 m/s: F0 55 00 00 00 00 04 13 00 | 00 A6 00 00 00 00 00 00 | ck.
  // Sum of bytes 0..16 = 0x202; folded 0x02 + 0x02 = 0x04; two's complement 0xFC.
  const auto p = rmp::encodeUsbToRmp(rmp::encodeMotion({0.5, 0}, rmp::scalingRmp200()));
  const std::array<std::uint8_t, 18> want = {0xF0, 0x55, 0x00, 0x00, 0x00, 0x00, 0x04, 0x13, 0x00,
                                             0x00, 0xA6, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xFC};
  EXPECT_EQ(p, want);
}

TEST(RmpProtocol, UsbPacketFromRmpIdEncoding) {
  CanFrame f;
  f.id = 0x402;
  f.data = {1, 2, 3, 4, 5, 6, 7, 8};
  const auto p = rmp::encodeUsbFromRmp(f);
  // id = (b4 << 3) | (b5 >> 5): 0x402 -> b4 0x80, b5 0x40.
  EXPECT_EQ(p[4], 0x80);
  EXPECT_EQ(p[5], 0x40);
  const auto r = rmp::parseUsbFromRmp(p);
  ASSERT_EQ(r.outcome, rmp::UsbOutcome::kFrame);
  EXPECT_EQ(r.frame, f);
  EXPECT_EQ(r.channel, 0xAA);
}

TEST(RmpProtocol, UsbResyncAfterGarbageAndCorruptChecksum) {
  CanFrame f;
  f.id = 0x401;
  f.data = {9, 9, 9, 9, 0, 0, 0, 0};
  auto good = rmp::encodeUsbFromRmp(f);
  auto bad = good;
  bad[10] ^= 0x40;  // a flipped bit: the checksum no longer matches
  std::vector<std::uint8_t> stream = {0x00, 0xF0, 0x12, 0x55};
  stream.insert(stream.end(), bad.begin(), bad.end());
  stream.insert(stream.end(), good.begin(), good.end());
  std::size_t corrupt = 0;
  std::span<const std::uint8_t> rest(stream);
  while (true) {
    const auto r = rmp::parseUsbFromRmp(rest);
    rest = rest.subspan(r.consumed);
    if (r.outcome == rmp::UsbOutcome::kCorrupt) {
      ++corrupt;
      continue;
    }
    ASSERT_EQ(r.outcome, rmp::UsbOutcome::kFrame);
    EXPECT_EQ(r.frame, f);
    break;
  }
  EXPECT_EQ(corrupt, 1u);
  // A short packet waits.
  EXPECT_EQ(rmp::parseUsbFromRmp(std::span(good).first(10)).outcome, rmp::UsbOutcome::kNeedMore);
}

// The simulator's side of the framing reads what the driver writes, and
// only that: an RMP -> host packet is not a command.
TEST(RmpProtocol, UsbPacketToRmpParsesBack) {
  CanFrame f;
  f.id = 0x413;
  f.data = {0, 0xA6, 0, 0, 0xFF, 0x10, 0, 0};
  std::vector<std::uint8_t> stream = {0x55, 0xF0};  // garbage before the packet
  const auto p = rmp::encodeUsbToRmp(f);
  stream.insert(stream.end(), p.begin(), p.end());
  std::span<const std::uint8_t> rest(stream);
  const auto r = rmp::parseUsbToRmp(rest);
  ASSERT_EQ(r.outcome, rmp::UsbOutcome::kFrame);
  EXPECT_EQ(r.frame, f);
  EXPECT_EQ(r.consumed, stream.size());
  auto bad = p;
  bad[12] ^= 1;
  EXPECT_EQ(rmp::parseUsbToRmp(bad).outcome, rmp::UsbOutcome::kCorrupt);
  EXPECT_EQ(rmp::parseUsbToRmp(std::span(p).first(17)).outcome, rmp::UsbOutcome::kNeedMore);
  const auto fromRmp = rmp::encodeUsbFromRmp(f);
  EXPECT_NE(rmp::parseUsbToRmp(fromRmp).outcome, rmp::UsbOutcome::kFrame);
}

TEST(RmpProtocol, UnknownModelNamesAreErrors) {
  EXPECT_THROW(rmp::scalingByName("rmp999"), horopter::Error);
  EXPECT_EQ(rmp::scalingByName("rmp400").countsPerMps, 332.0);
}

TEST(RmpProtocol, MotorStatusHeartbeat) {
  CanFrame f;
  f.id = 0x680;
  f.data = {0, 0, 0, 0x80, 0, 0, 0, 0};
  EXPECT_EQ(rmp::decodeMotorStatus(f), true);
  f.data[3] = 0x00;
  EXPECT_EQ(rmp::decodeMotorStatus(f), false);
  f.id = 0x401;
  EXPECT_EQ(rmp::decodeMotorStatus(f), std::nullopt);
  EXPECT_EQ(rmp::decodeMotorStatus(rmp::encodeMotorStatus(true)), true);
}
