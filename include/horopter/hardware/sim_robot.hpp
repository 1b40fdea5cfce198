// A whole simulated robot for `horopter run --robot sim`: the real drivers
// talking to simulated devices, plus a telemetry log.
//
//   - head: a simulated DYNAMIXEL bus (pan ID 1, tilt ID 2, left/right
//     vergence IDs 3/4) on a real pseudo-terminal, driven by DynamixelHead
//     through SerialPort, exactly as a USB adapter would be;
//   - base: a simulated Segway RMP 200 on the in-process CAN bus, driven by
//     RmpBase (50 Hz commands, 200 ms watchdog) with odometry decoded from
//     the status frames.
//
// Use from the pipeline (the stage that steers the head and the base):
//
//   horopter::hw::SimulatedRobot robot;                // starts devices and drivers
//   horopter::hw::TelemetryLog log("out/telemetry.jsonl");
//   ... per frame, in the stage that decides:
//   robot.head().command({panRad, tiltRad, vergenceRad});   // never blocks
//   robot.base().command({linearMps, angularRadPerS});      // keep sending (watchdog)
//   if (auto m = robot.head().measured()) geometry uses m->angles (the dynamic horopter)
//   log.write(robot.sample());                              // one JSON line
//   ... at the end: robot.shutdown() (also in the destructor): zero velocity, threads joined.
//
// hw::Head& and hw::Base& are the committed interfaces (head.hpp, base.hpp),
// so a stage written against them runs unchanged on the real drivers.
#pragma once

#include <fstream>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "horopter/hardware/base.hpp"
#include "horopter/hardware/head.hpp"
#include "horopter/hardware/head_health.hpp"
#include "horopter/hardware/rmp_base.hpp"

namespace horopter::hw {

struct TelemetrySample {
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

// JSON lines: one object per sample, flushed per line (a crash keeps what was written).
class TelemetryLog {
 public:
  explicit TelemetryLog(const std::string& path);  // throws horopter::Error if it cannot write
  void write(const TelemetrySample& sample);
  static std::string toJson(const TelemetrySample& sample);
  long lines() const { return lines_; }

 private:
  std::mutex mutex_;
  std::ofstream out_;
  long lines_ = 0;
};

struct SimulatedRobotOptions {
  bool vergence = true;
  RmpBaseOptions base;  // safety limits etc.; startThread is forced on
};

class SimulatedRobot {
 public:
  explicit SimulatedRobot(SimulatedRobotOptions options = {});
  ~SimulatedRobot();
  SimulatedRobot(const SimulatedRobot&) = delete;
  SimulatedRobot& operator=(const SimulatedRobot&) = delete;

  Head& head();
  Base& base();
  // The latest commands, measurements, odometry, e-stop and faults.
  TelemetrySample sample() const;
  // Ground truth of the simulated base (for tests and the log's sanity).
  double trueX() const;
  void shutdown();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace horopter::hw
