#include "horopter/app/robot_stage.hpp"

#include <cstdio>
#include <opencv2/imgproc.hpp>

#include "horopter/core/error.hpp"
#include "horopter/interaction/tracking.hpp"
#include "horopter/movement/movement.hpp"

namespace horopter {

namespace {

class RobotStage final : public Stage {
 public:
  explicit RobotStage(RobotStageOptions options) : options_(options) {
    if ((options_.log == nullptr) != (options_.telemetrySource == nullptr))
      throw Error("the robot stage needs both a telemetry source and a log, or neither");
  }
  std::string name() const override { return "robot"; }

  void process(Frame& f) override {
    if (options_.emergencyStop && options_.emergencyStop->load() && !stopped_) {
      if (options_.base) options_.base->emergencyStop();
      if (options_.head) options_.head->halt();
      stopped_ = true;
    }
    if (stopped_) {
      record(f);
      return;
    }
    if (options_.head && f.tracking && f.tracking->headCommand) {
      hw::HeadAngles target = *f.tracking->headCommand;
      if (f.movement && f.movement->headOffset) {
        target.pan += f.movement->headOffset->pan;
        target.tilt += f.movement->headOffset->tilt;
      }
      options_.head->command(target);
    }
    // The movement stage gives a velocity every frame (zero when idle), which
    // keeps the base's 200 ms watchdog fed while the pipeline runs.
    if (options_.base && f.movement) options_.base->command(f.movement->base);
    record(f);
  }

 private:
  void record(Frame& f) {
    auto state = std::make_shared<RobotState>();
    state->frame = f.index;
    if (options_.telemetrySource) {
      state->telemetry = options_.telemetrySource->sample();
      options_.log->write(state->telemetry);
    }
    f.robot = std::move(state);
  }

  RobotStageOptions options_;
  bool stopped_ = false;
};

}  // namespace

std::unique_ptr<Stage> makeRobotStage(RobotStageOptions options) {
  return std::make_unique<RobotStage>(options);
}

void drawRobotOverlay(cv::Mat& bgr, const RobotState& state) {
  if (bgr.type() != CV_8UC3) throw Error("the robot overlay draws on a BGR image (CV_8UC3)");
  const hw::TelemetrySample& t = state.telemetry;
  char lines[3][128];
  if (t.headMeasured)
    std::snprintf(lines[0], sizeof lines[0], "head (measured) pan %+.1f tilt %+.1f deg",
                  t.headMeasured->angles.pan * 57.29578, t.headMeasured->angles.tilt * 57.29578);
  else
    std::snprintf(lines[0], sizeof lines[0], "head: no measurement yet");
  std::snprintf(lines[1], sizeof lines[1], "base sent v %+.2f m/s  w %+.2f rad/s%s",
                t.baseSent.linear, t.baseSent.angular, t.emergencyStop ? "  E-STOP" : "");
  if (t.odometry)
    std::snprintf(lines[2], sizeof lines[2], "odometry x %+.2f y %+.2f m  heading %+.0f deg",
                  t.odometry->x, t.odometry->y, t.odometry->heading * 57.29578);
  else
    std::snprintf(lines[2], sizeof lines[2], "odometry: no status yet");
  const double scale = bgr.cols / 1280.0 + 0.2;
  const int step = static_cast<int>(22 * scale / 0.7) + 2;
  for (int i = 0; i < 3; ++i) {
    const cv::Point at(8, bgr.rows - 8 - (2 - i) * step);
    cv::putText(bgr, lines[i], at, cv::FONT_HERSHEY_SIMPLEX, scale, {0, 0, 0}, 3, cv::LINE_AA);
    cv::putText(bgr, lines[i], at, cv::FONT_HERSHEY_SIMPLEX, scale, {255, 255, 255}, 1,
                cv::LINE_AA);
  }
}

}  // namespace horopter
