// The actuation stage: each frame's head command (tracking, plus the
// movement's gesture offset) and base velocity (movement) go to a robot's
// head and base through the hw::Head / hw::Base interfaces, which never
// block; with a telemetry log, one JSON line per frame records what was
// commanded and what the robot measured. `horopter run --robot sim` puts it
// last, on a SimulatedRobot (real drivers on simulated devices).
#pragma once

#include "horopter/core/export.hpp"

#include <atomic>
#include <memory>
#include <opencv2/core.hpp>

#include "horopter/app/frame.hpp"
#include "horopter/hardware/base.hpp"
#include "horopter/hardware/head.hpp"
#include "horopter/hardware/telemetry.hpp"

namespace horopter {

// What the robot stage saw after commanding the robot for a frame.
struct HOROPTER_API RobotState {
  std::int64_t frame = 0;
  hw::TelemetrySample telemetry;
};

struct HOROPTER_API RobotStageOptions {
  hw::Head* head = nullptr;  // not owned; null: no head commands
  hw::Base* base = nullptr;  // not owned; null: no base commands
  // Optional: the telemetry source and log (not owned; both or neither).
  const hw::TelemetrySource* telemetrySource = nullptr;
  hw::TelemetryLog* log = nullptr;
  // Optional: once it reads true (Ctrl-C), the base's emergency stop is
  // latched and no more commands are sent.
  const std::atomic<bool>* emergencyStop = nullptr;
};

// The stage "robot". Needs the tracking stage (head) and/or the movement
// stage (base) before it; a frame without them commands nothing new (the
// base then stops by its own watchdog).
HOROPTER_API std::unique_ptr<Stage> makeRobotStage(RobotStageOptions options);

// The robot's measured head angles, base velocity, odometry and e-stop, as
// text in the bottom left of a BGR image (CV_8UC3).
HOROPTER_API void drawRobotOverlay(cv::Mat& bgr, const RobotState& state);

}  // namespace horopter
