// A simulated Segway RMP behind a CanTransport (the device side of an
// InProcessCanBus): it obeys 0x413 motion frames and the reset-integrators
// configuration command, moves a kinematic unicycle model, and reports the
// 0x400..0x407 status series, byte for byte as rmp_protocol.hpp encodes it,
// so the real RmpBase driver's odometry follows the commands.
//
// Checked only against our own reading of the protocol (there is no RMP
// here); see the tests for what is checked against libsegwayrmp's layout.
#pragma once

#include <atomic>
#include <mutex>
#include <thread>

#include <memory>
#include <string>

#include "horopter/hardware/pty.hpp"
#include "horopter/hardware/rmp_protocol.hpp"
#include "horopter/hardware/transport.hpp"

namespace horopter::hw {

enum class SimRmpFault {
  kNone,
  kSilent,        // sends no status (the driver must time out)
  kBadLength,     // a status frame with 3 data bytes
  kMissingFrame,  // a series without 0x404
  kWildValues,    // 0x402 with wheel speeds of 32767 counts (99 m/s), 0x406 with mode 9
};

struct SimRmpOptions {
  rmp::Scaling scaling = rmp::scalingRmp200();
  std::chrono::milliseconds period{10};  // status series rate (100 Hz)
  double trackWidth = 0.54;              // m, wheel to wheel (for the wheel speeds)
  bool startThread = true;
};

struct SimRmpTruth {
  double x = 0, y = 0, heading = 0;
  BaseVelocity velocity;
  long motionFrames = 0;
  long resets = 0;
};

class SimRmp {
 public:
  SimRmp(CanTransport& bus, SimRmpOptions options = {});
  ~SimRmp();
  SimRmp(const SimRmp&) = delete;
  SimRmp& operator=(const SimRmp&) = delete;

  // One cycle: read commands, integrate since the last step, report a series.
  void step(Clock::time_point now);
  void injectFault(SimRmpFault fault, int series);
  SimRmpTruth truth() const;
  // The RMP's own e-stop button: motors disabled (0x680 says so), the base stops.
  void pressEmergencyStop(bool pressed);
  void stop();

 private:
  void run();
  CanTransport& bus_;
  SimRmpOptions options_;
  mutable std::mutex mutex_;
  rmp::Status reported_;
  SimRmpTruth truth_;
  BaseVelocity commanded_;
  bool haveTime_ = false;
  Clock::time_point last_{};
  SimRmpFault fault_ = SimRmpFault::kNone;
  bool buttonPressed_ = false;
  int faultSeries_ = 0;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

// A simulated RMP behind its USB interface on a pseudo-terminal: the real
// driver opens port() with SerialPort and RmpUsbCan, exactly as it opens
// /dev/ttyUSB1, so every command crosses a real tty and the 18-byte USB
// framing in both directions.
class SimRmpOnPty {
 public:
  explicit SimRmpOnPty(SimRmpOptions options = {});
  ~SimRmpOnPty();
  SimRmpOnPty(const SimRmpOnPty&) = delete;
  SimRmpOnPty& operator=(const SimRmpOnPty&) = delete;

  const std::string& port() const { return pty_.slavePath(); }
  SimRmp& rmp() { return *rmp_; }

 private:
  PseudoTerminal pty_;
  std::unique_ptr<CanTransport> usb_;  // the device side of the USB framing
  std::unique_ptr<SimRmp> rmp_;
};

}  // namespace horopter::hw
