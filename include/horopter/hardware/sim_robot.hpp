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

#include <memory>
#include <optional>
#include <string>

#include "horopter/hardware/base.hpp"
#include "horopter/hardware/head.hpp"
#include "horopter/hardware/head_health.hpp"
#include "horopter/hardware/rmp_base.hpp"
#include "horopter/hardware/telemetry.hpp"

namespace horopter::hw {

struct SimulatedRobotOptions {
  bool vergence = true;
  RmpBaseOptions base;  // safety limits etc.; startThread is forced on
};

class SimulatedRobot : public TelemetrySource {
 public:
  explicit SimulatedRobot(SimulatedRobotOptions options = {});
  ~SimulatedRobot();
  SimulatedRobot(const SimulatedRobot&) = delete;
  SimulatedRobot& operator=(const SimulatedRobot&) = delete;

  Head& head();
  Base& base();
  // The latest commands, measurements, odometry, e-stop and faults.
  TelemetrySample sample() const override;
  // Ground truth of the simulated base (for tests and the log's sanity).
  double trueX() const;
  void shutdown();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace horopter::hw
