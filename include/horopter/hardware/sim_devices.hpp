// Simulated serial devices on a pseudo-terminal, byte-exact: a DYNAMIXEL
// Protocol 2.0 bus of X-series servos, and a FLIR PTU speaking the ASCII
// command set. The real drivers open slavePath() through SerialPort.
// Their behaviour follows our reading of the documentation (see
// dynamixel_protocol.hpp and ptu_protocol.hpp); it has not been compared
// with real hardware.
//
// Fault injection applies to the next `count` replies: a corrupt checksum, a
// short frame (the first half only), garbage instead of the reply, no reply,
// or a disconnect (the pty hangs up; the driver's link goes down).
#pragma once

#include <atomic>
#include <map>
#include <mutex>
#include <string>
#include <thread>

#include "horopter/hardware/dynamixel_protocol.hpp"
#include "horopter/hardware/pty.hpp"

namespace horopter::hw {

enum class DeviceFault { kNone, kCorruptChecksum, kShortFrame, kGarbage, kNoReply, kDisconnect };

class SimDynamixelBus {
 public:
  // Servos with these IDs, all at 0 rad, torque off, model number 1020 (XM430-W350).
  explicit SimDynamixelBus(std::vector<std::uint8_t> ids, dxl::ServoModel model = {});
  ~SimDynamixelBus();
  SimDynamixelBus(const SimDynamixelBus&) = delete;
  SimDynamixelBus& operator=(const SimDynamixelBus&) = delete;

  const std::string& port() const { return pty_.slavePath(); }
  void injectFault(DeviceFault fault, int count = 1);
  // The next `count` status replies become status packets from the same ID,
  // with a valid CRC and these parameters instead (the ERROR byte first; empty:
  // no ERROR byte at all): a device that talks the protocol but says nonsense.
  void injectStatus(std::vector<std::uint8_t> params, int count = 1);
  double positionRad(std::uint8_t id) const;
  std::int32_t goalTicks(std::uint8_t id) const;
  bool torqueOn(std::uint8_t id) const;
  // EEPROM limits (defaults 0..4095 ticks, Velocity Limit 167 units). Goals are clamped to them.
  void setLimits(std::uint8_t id, std::int32_t minTicks, std::int32_t maxTicks,
                 std::int32_t velocityLimit);
  long packetsReceived() const { return packets_; }
  long corruptReceived() const { return corruptIn_; }

 private:
  struct Servo {
    double position = 2048;  // ticks, fractional while moving
    std::int32_t goal = 2048;
    std::int32_t profileVelocity = 0;  // 0: as fast as the Velocity Limit allows
    std::int32_t minLimit = 0, maxLimit = 4095, velocityLimit = 167;
    bool torque = false;
  };
  void run();
  void handle(const dxl::Packet& p);
  void reply(std::vector<std::uint8_t> bytes);
  void advance(double seconds);
  std::vector<std::uint8_t> readTable(const Servo& s, std::uint16_t address,
                                      std::uint16_t length) const;
  void writeTable(Servo& s, std::uint16_t address, std::span<const std::uint8_t> data);

  PseudoTerminal pty_;
  dxl::ServoModel model_;
  mutable std::mutex mutex_;
  std::map<std::uint8_t, Servo> servos_;
  DeviceFault fault_ = DeviceFault::kNone;
  int faultCount_ = 0;
  std::vector<std::uint8_t> injectedParams_;
  int injectedCount_ = 0;
  std::atomic<long> packets_{0}, corruptIn_{0};
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

struct SimPtuOptions {
  double resolutionArcSec = 185.1428;  // PTU-D46-like
  long panMin = -3090, panMax = 3090, tiltMin = -907, tiltMax = 604;
  long maxSpeed = 2900;  // positions/s
};

class SimPtu {
 public:
  explicit SimPtu(SimPtuOptions options = {});
  ~SimPtu();
  SimPtu(const SimPtu&) = delete;
  SimPtu& operator=(const SimPtu&) = delete;

  const std::string& port() const { return pty_.slavePath(); }
  void injectFault(DeviceFault fault, int count = 1);
  // The next `count` replies are this line instead (e.g. "* inf"): a unit that
  // speaks the grammar but says nonsense.
  void injectReply(std::string line, int count = 1);
  long position(bool pan) const;
  long commandsReceived() const { return commands_; }

 private:
  void run();
  std::string handle(const std::string& command);
  void advance(double seconds);

  PseudoTerminal pty_;
  SimPtuOptions options_;
  mutable std::mutex mutex_;
  double pan_ = 0, tilt_ = 0;
  long panTarget_ = 0, tiltTarget_ = 0, panSpeed_ = 1000, tiltSpeed_ = 1000;
  bool echo_ = true, terse_ = false;
  DeviceFault fault_ = DeviceFault::kNone;
  int faultCount_ = 0;
  std::string injectedLine_;
  int injectedCount_ = 0;
  std::atomic<long> commands_{0};
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace horopter::hw
