// The Segway RMP (RMP 50/100/200/400 family) CAN interface, pure functions.
//
// Sources: Segway "RMP Interface Guide" (CAN messages 0x400-0x407 and 0x413)
// as implemented by libsegwayrmp (github.com/segwayrmp/libsegwayrmp,
// src/segwayrmp.cc: move(), SetConstantsBySegwayType_(), ParsePacket_();
// src/impl/rmp_io.cc: the USB framing, sendPacket(), getPacket(),
// computeChecksum()). Facts only; the code here is ours.
//
// Host -> RMP, id 0x413, 8 bytes, big-endian int16s:
//   [0..1] velocity command (counts = m/s * countsPerMps)
//   [2..3] yaw-rate command (counts = deg/s * countsPerDegPerS; positive turns left)
//   [4..5] configuration command (0 = none; 0x0A max velocity scale, 0x0B max
//          acceleration scale, 0x0C max turn scale, 0x0D gain schedule,
//          0x0E current limit scale, 0x0F balance lock, 0x10 operational
//          mode, 0x32 reset integrators)
//   [6..7] configuration parameter
//   id 0x412: shutdown.
// RMP -> host, one series per control cycle, in order 0x400 .. 0x407:
//   0x400 first of a series (no data we use)
//   0x401 pitch, pitch rate, roll, roll rate       int16 / countsPerDegPerS -> deg, deg/s
//   0x402 left, right wheel speed                  int16 / countsPerMps -> m/s
//         yaw rate                                 int16 / countsPerDegPerS -> deg/s
//         servo frames                             uint16 * 0.01 s
//   0x403 integrated left, right wheel displacement int32 / countsPerMetre -> m
//   0x404 integrated fore-aft displacement          int32 / countsPerMetre -> m
//         integrated yaw displacement               int32 / countsPerRev -> revolutions
//   0x405 left, right motor torque                 int16 / countsPerNm -> N m
//   0x406 operational mode (0 disabled, 1 tractor, 2 balance, 3 power down),
//         gain schedule (0 light, 1 tall, 2 heavy),
//         UI battery voltage                       uint16 * 0.0125 + 1.4 V
//         powerbase battery voltage                uint16 / 4 V
//   0x407 commanded velocity                       int16 / countsPerMps -> m/s
//         commanded yaw rate                       int16 (libsegwayrmp divides by 1024;
//                                                  we keep the raw counts)
//   0x680 motor status (outside the series): data[3] == 0x80 motors enabled,
//         anything else: the RMP's own emergency stop is pressed
//   int16 values are big-endian; an int32 is sent as two big-endian 16-bit
//   words, the LOW word first (libsegwayrmp's getInt()).
//
// USB framing (the RMP's FTDI USB interface, 18 bytes per CAN frame):
//   host -> RMP  F0 55 ch 00 00 00 idH idL 00 d0..d7 ck   (libsegwayrmp sends ch 0)
//   RMP -> host  F0 55 AA|BB 00 b4 b5 .. .. .. d0..d7 ck  id = ((b4 << 3) | (b5 >> 5)) & 0x7FF;
//                channel 0xBB (the second CAN channel) is ignored
//   ck: sum of bytes 0..16, carries folded twice into 8 bits, then two's complement.
#pragma once

#include "horopter/core/export.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <optional>
#include <span>
#include <string>

#include "horopter/hardware/base.hpp"
#include "horopter/hardware/transport.hpp"

namespace horopter::hw::rmp {

constexpr std::uint32_t kCommandId = 0x413;
constexpr std::uint32_t kShutdownId = 0x412;
constexpr std::uint32_t kStatusFirstId = 0x400;
constexpr std::uint32_t kStatusLastId = 0x407;
constexpr std::uint32_t kMotorStatusId = 0x680;
constexpr std::size_t kUsbFrameSize = 18;

// The one place where SI units meet counts (libsegwayrmp SetConstantsBySegwayType_).
struct HOROPTER_API Scaling {
  const char* model;
  double countsPerMps;
  double countsPerDegPerS;
  double countsPerMetre;
  double countsPerRev;
  double countsPerNm;
};
HOROPTER_API Scaling scalingRmp200();  // RMP 200 and 400: 332, 7.8, 33215, 112644, 1094
HOROPTER_API Scaling scalingRmp100();  // RMP 50 and 100:  401, 7.8, 40181, 117031, 1463
// "rmp200", "rmp400", "rmp100", "rmp50"; throws horopter::Error otherwise.
HOROPTER_API Scaling scalingByName(const std::string& name);

enum class ConfigCommand : std::uint16_t {
  kNone = 0,
  kMaxVelocityScale = 0x0A,
  kMaxAccelerationScale = 0x0B,
  kMaxTurnScale = 0x0C,
  kGainSchedule = 0x0D,
  kCurrentLimitScale = 0x0E,
  kBalanceLock = 0x0F,
  kOperationalMode = 0x10,
  kResetIntegrators = 0x32,
};

// The velocity/turn command; values beyond int16 are clamped (the caller limits first).
HOROPTER_API CanFrame encodeMotion(const BaseVelocity& velocity, const Scaling& scaling);
HOROPTER_API CanFrame encodeConfig(ConfigCommand command, std::uint16_t parameter);
// The counts a command frame carries (for the simulator and the tests).
struct HOROPTER_API MotionCounts {
  std::int16_t velocity = 0;
  std::int16_t yawRate = 0;
  std::uint16_t configCommand = 0;
  std::uint16_t configParameter = 0;
};
HOROPTER_API MotionCounts
decodeMotion(const CanFrame& frame);  // throws if not a 0x413 frame of 8 bytes
HOROPTER_API BaseVelocity countsToVelocity(const MotionCounts& counts, const Scaling& scaling);

// Everything the status series reports, in SI units (radians, not degrees).
struct HOROPTER_API Status {
  double pitch = 0, pitchRate = 0, roll = 0, rollRate = 0;       // rad, rad/s
  double leftWheelSpeed = 0, rightWheelSpeed = 0;                // m/s
  double yawRate = 0;                                            // rad/s, positive left
  double servoFrames = 0;                                        // s
  double leftWheelDisplacement = 0, rightWheelDisplacement = 0;  // m
  double foreAftDisplacement = 0;                                // m
  double yawDisplacement = 0;                                    // rad
  double leftMotorTorque = 0, rightMotorTorque = 0;              // N m
  int operationalMode = 0;
  int gainSchedule = 0;
  double uiBatteryVolts = 0, powerbaseBatteryVolts = 0;
  double commandedVelocity = 0;    // m/s
  int commandedYawRateCounts = 0;  // raw
  unsigned receivedMask = 0;       // bit (id - 0x400) per frame decoded in this series
};

// Bounds no RMP of this family comes near; a status beyond them is garbage.
constexpr double kMaxPlausibleSpeed = 10.0;                            // m/s (36 km/h)
constexpr double kMaxPlausibleRate = 1000.0 * std::numbers::pi / 180;  // rad/s (1000 deg/s)

// Decodes one status frame into `status`; false for ids outside 0x400..0x407
// (other traffic on the bus). Throws horopter::Error, leaving `status` as it
// was, for a status frame with the wrong length (8 data bytes, 0x400 up to 8)
// or an implausible value: |pitch|, |roll| > 180 deg, a rate beyond
// kMaxPlausibleRate, a wheel or commanded speed beyond kMaxPlausibleSpeed, an
// operational mode outside 0..3, a gain schedule outside 0..2.
HOROPTER_API bool decodeStatusFrame(const CanFrame& frame, const Scaling& scaling, Status& status);
// The 0x680 motor status: true when the motors are enabled, false when the
// RMP's own e-stop is pressed; nullopt for any other frame.
HOROPTER_API std::optional<bool> decodeMotorStatus(const CanFrame& frame);
HOROPTER_API CanFrame encodeMotorStatus(bool motorsEnabled);
// The eight frames of a series (for the simulator), the inverse of the decoder
// up to the counts' resolution.
HOROPTER_API std::array<CanFrame, 8> encodeStatusFrames(const Status& status,
                                                        const Scaling& scaling);

// USB framing.
HOROPTER_API std::uint8_t usbChecksum(std::span<const std::uint8_t> first17);
HOROPTER_API std::array<std::uint8_t, kUsbFrameSize> encodeUsbToRmp(const CanFrame& frame,
                                                                    std::uint8_t channel = 0);
HOROPTER_API std::array<std::uint8_t, kUsbFrameSize> encodeUsbFromRmp(const CanFrame& frame,
                                                                      std::uint8_t channel = 0xAA);

enum class UsbOutcome { kFrame, kNeedMore, kCorrupt };
struct HOROPTER_API UsbParse {
  UsbOutcome outcome = UsbOutcome::kNeedMore;
  CanFrame frame;
  std::uint8_t channel = 0;
  std::size_t consumed = 0;
  std::string error;
};
// The first RMP -> host frame in `buffer` (resynchronises on F0 55 AA|BB).
HOROPTER_API UsbParse parseUsbFromRmp(std::span<const std::uint8_t> buffer);
// The first host -> RMP frame in `buffer` (resynchronises on F0 55 00|01):
// what the RMP's USB interface reads, for the simulator behind a pty.
HOROPTER_API UsbParse parseUsbToRmp(std::span<const std::uint8_t> buffer);

}  // namespace horopter::hw::rmp
