// A robot's telemetry: one sample of what was commanded, measured and
// faulted, where samples come from, and a JSON-lines log of them. The robot
// stage writes it for whatever robot it drives.
#pragma once

#include "horopter/core/export.hpp"

#include <fstream>
#include <mutex>
#include <optional>
#include <string>

#include "horopter/hardware/base.hpp"
#include "horopter/hardware/head.hpp"
#include "horopter/hardware/head_health.hpp"
#include "horopter/hardware/rmp_base.hpp"

namespace horopter::hw {

struct HOROPTER_API TelemetrySample {
  double t = 0;  // seconds since the robot started
  std::optional<HeadAngles> headCommanded;
  std::optional<HeadMeasurement> headMeasured;
  std::optional<BaseVelocity> baseCommanded;  // what the caller asked
  BaseVelocity baseSent;                      // what the driver sent after the safety rules
  std::optional<Odometry> odometry;           // pose and measured velocity
  bool emergencyStop = false;
  HeadHealth head;
  BaseHealth base;
};

// Where samples come from: a robot that knows its commands, measurements,
// odometry and faults (hw::SimulatedRobot; a real robot's wiring likewise).
class HOROPTER_API TelemetrySource {
 public:
  virtual ~TelemetrySource() = default;
  virtual TelemetrySample sample() const = 0;
};

// JSON lines: one object per sample, flushed per line (a crash keeps what was written).
// The constructor and write() throw horopter::Error, naming the file and the
// reason, when the log cannot be opened or a line cannot be written (a full disk).
class HOROPTER_API TelemetryLog {
 public:
  explicit TelemetryLog(const std::string& path);
  void write(const TelemetrySample& sample);
  static std::string toJson(const TelemetrySample& sample);
  long lines() const { return lines_; }

 private:
  std::mutex mutex_;
  std::string path_;
  std::ofstream out_;
  long lines_ = 0;
};

}  // namespace horopter::hw
