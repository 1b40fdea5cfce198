// Transports and byte-exact driver start-up: the RMP's USB framing through a
// scripted byte stream, the DYNAMIXEL head's first exchanges against the
// e-manual's example packets, and the errors of ports that do not exist.
#include <gtest/gtest.h>

#include <sstream>

#include "horopter/core/error.hpp"
#include "horopter/hardware/can_transports.hpp"
#include "horopter/hardware/dynamixel_head.hpp"
#include "horopter/hardware/rmp_protocol.hpp"
#include "horopter/hardware/scripted_transport.hpp"
#include "horopter/hardware/serial_port.hpp"

using namespace horopter::hw;
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
Bytes operator+(Bytes a, const Bytes& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}
template <std::size_t N>
Bytes bytes(const std::array<std::uint8_t, N>& a) {
  return Bytes(a.begin(), a.end());
}
}  // namespace

TEST(RmpUsbTransport, FramesCrossTheByteStreamBothWays) {
  auto script = std::make_unique<ScriptedTransport>();
  ScriptedTransport& s = *script;
  const CanFrame command = rmp::encodeMotion({0.5, 0}, rmp::scalingRmp200());
  CanFrame status;
  status.id = 0x402;
  status.data = {0x01, 0x4C, 0x01, 0x4C, 0, 0, 0, 0};
  CanFrame channelB = status;
  channelB.data[0] = 0x77;
  auto corrupt = rmp::encodeUsbFromRmp(status);
  corrupt[12] ^= 0x01;
  // Reply: garbage, a corrupt packet, a channel-B copy (ignored), the good packet.
  s.expect(bytes(rmp::encodeUsbToRmp(command)), Bytes{0x00, 0x13} + bytes(corrupt) +
                                                    bytes(rmp::encodeUsbFromRmp(channelB, 0xBB)) +
                                                    bytes(rmp::encodeUsbFromRmp(status)));
  RmpUsbCan usb(std::move(script));
  usb.send(command);
  CanFrame got;
  ASSERT_TRUE(usb.receive(got, std::chrono::milliseconds(1)));
  EXPECT_EQ(got, status);
  EXPECT_EQ(usb.corruptPackets(), 1);
  EXPECT_FALSE(usb.receive(got, std::chrono::milliseconds(1)));  // nothing more: no frame invented
  EXPECT_TRUE(s.mismatches().empty());
}

TEST(RmpUsbTransport, ACutLinkIsALinkError) {
  auto script = std::make_unique<ScriptedTransport>();
  script->cut();
  RmpUsbCan usb(std::move(script));
  EXPECT_THROW(usb.send(CanFrame{}), LinkError);
}

// The driver's first bytes are the e-manual's own examples: Ping ID 1, and the
// Sync Read of Present Position (132, 4 bytes) from IDs 1 and 2, answered with
// the manual's status packets (166 and 2079).
TEST(DynamixelHeadScripted, StartUpUsesTheManualsPackets) {
  auto script = std::make_unique<ScriptedTransport>();
  ScriptedTransport& s = *script;
  s.expect(hex("FF FF FD 00 01 03 00 01 19 4E"), hex("FF FF FD 00 01 07 00 55 00 06 04 26 65 5D"));
  s.expect(dxl::pingPacket(2), dxl::statusPacket(2, 0, Bytes{0xFC, 0x03, 0x2D}));
  // Velocity Limit (44), Max/Min Position Limit (48, 52) of pan and tilt: 167, 4095, 0.
  const Bytes limits =
      dxl::littleEndian(167, 4) + dxl::littleEndian(4095, 4) + dxl::littleEndian(0, 4);
  s.expect(dxl::readPacket(1, 44, 12), dxl::statusPacket(1, 0, limits));
  s.expect(dxl::readPacket(2, 44, 12), dxl::statusPacket(2, 0, limits));
  s.expect(dxl::writePacket(1, 64, Bytes{1}), hex("FF FF FD 00 01 04 00 55 00 A1 0C"));
  s.expect(dxl::writePacket(2, 64, Bytes{1}), dxl::statusPacket(2, 0, {}));
  s.expect(hex("FF FF FD 00 FE 09 00 82 84 00 04 00 01 02 CE FA"),
           hex("FF FF FD 00 01 08 00 55 00 A6 00 00 00 8C C0 "
               "FF FF FD 00 02 08 00 55 00 1F 08 00 00 BA BE"));
  DynamixelHeadOptions o;
  o.replyTimeout = std::chrono::milliseconds(1);
  DynamixelHead head(std::move(script), o);
  EXPECT_EQ(head.modelNumbers(), (std::vector<int>{1030, 1020}));
  const auto m = head.measured();
  ASSERT_TRUE(m.has_value());
  const dxl::ServoModel x;
  EXPECT_DOUBLE_EQ(m->angles.pan, dxl::ticksToRadians(166, x));
  EXPECT_DOUBLE_EQ(m->angles.tilt, dxl::ticksToRadians(2079, x));
  head.shutdown();
  EXPECT_TRUE(s.scriptDone());
  for (const std::string& mm : s.mismatches())
    EXPECT_EQ(mm.rfind("unexpected write", 0), 0u) << mm;
}

TEST(DynamixelHeadScripted, ADeviceErrorIsNamed) {
  auto script = std::make_unique<ScriptedTransport>();
  script->expect(dxl::pingPacket(1), dxl::statusPacket(1, 0, Bytes{0xFC, 0x03, 0x2D}));
  script->expect(dxl::pingPacket(2), dxl::statusPacket(2, 0, Bytes{0xFC, 0x03, 0x2D}));
  const Bytes limits =
      dxl::littleEndian(167, 4) + dxl::littleEndian(4095, 4) + dxl::littleEndian(0, 4);
  script->expect(dxl::readPacket(1, 44, 12), dxl::statusPacket(1, 0, limits));
  script->expect(dxl::readPacket(2, 44, 12), dxl::statusPacket(2, 0, limits));
  // Torque Enable refused with "data range error" (4) on every retry.
  for (int i = 0; i < 3; ++i)
    script->expect(dxl::writePacket(1, 64, Bytes{1}), dxl::statusPacket(1, 4, {}));
  DynamixelHeadOptions o;
  o.replyTimeout = std::chrono::milliseconds(1);
  try {
    DynamixelHead head(std::move(script), o);
    FAIL() << "a refused Torque Enable must not open";
  } catch (const horopter::Error& e) {
    EXPECT_NE(std::string(e.what()).find("Torque Enable"), std::string::npos) << e.what();
  }
}

TEST(Ports, MissingOrWrongDevicesAreClearErrors) {
  try {
    SerialPort p("/dev/horopter-no-such-port");
    FAIL();
  } catch (const horopter::Error& e) {
    EXPECT_NE(std::string(e.what()).find("no such device"), std::string::npos) << e.what();
  }
  EXPECT_THROW(SerialPort("/dev/null"), horopter::Error);  // not a tty
  EXPECT_THROW(baudConstant(12345), horopter::Error);
  EXPECT_THROW(SocketCan("horopter-no-can"), horopter::Error);
  EXPECT_THROW(SocketCan(""), horopter::Error);
}
