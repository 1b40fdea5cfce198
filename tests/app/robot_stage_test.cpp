// The actuation stage: tracking's head command and the movement's base
// velocity reach a simulated robot (real drivers on simulated devices)
// through the pipeline, with one telemetry line per frame.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <thread>

#include "horopter/app/robot_stage.hpp"
#include "horopter/core/error.hpp"
#include "horopter/hardware/sim_robot.hpp"
#include "horopter/interaction/tracking.hpp"
#include "horopter/movement/movement.hpp"

namespace horopter {
namespace {

using namespace std::chrono_literals;

// Frames paced like a 100 frames/s camera, so the robot's threads run meanwhile.
class PacedSource : public FrameSource {
 public:
  explicit PacedSource(int count) : count_(count) {}
  std::string name() const override { return "paced"; }
  bool next(Frame& frame) override {
    if (produced_ == count_) return false;
    std::this_thread::sleep_for(10ms);
    frame.left = cv::Mat(4, 4, CV_8UC3, cv::Scalar::all(0));
    ++produced_;
    return true;
  }

 private:
  int count_, produced_ = 0;
};

// What tracking and movement analysis would decide: look right, drive forward.
void decide(Frame& f) {
  auto tracking = std::make_shared<TrackingState>();
  tracking->headCommand = hw::HeadAngles{0.15, -0.05, 0.06};
  f.tracking = tracking;
  auto movement = std::make_shared<MovementState>();
  movement->base = {0.3, 0.0};
  f.movement = movement;
}

TEST(RobotStage, HeadTurnsAndBaseDrivesWithOneTelemetryLinePerFrame) {
  hw::SimulatedRobot robot;
  const auto path = std::filesystem::temp_directory_path() / "horopter_robot_stage_test.jsonl";
  std::int64_t lastFrameWithTelemetry = -1;
  {
    hw::TelemetryLog log(path.string());
    PipelineOptions options;
    options.onFrame = [&](const Frame& f) {
      ASSERT_TRUE(f.robot);
      lastFrameWithTelemetry = f.robot->frame;
    };
    Pipeline pipeline(options);
    pipeline.add(makeStage("decide", decide));
    pipeline.add(makeRobotStage({&robot.head(), &robot.base(), &robot, &log}));
    PacedSource source(60);
    const RunSummary summary = pipeline.run(source);
    EXPECT_EQ(summary.completed, 60);
    EXPECT_EQ(log.lines(), 60);
  }
  EXPECT_EQ(lastFrameWithTelemetry, 59);
  const hw::TelemetrySample s = robot.sample();
  ASSERT_TRUE(s.headMeasured.has_value());
  EXPECT_GT(s.headMeasured->angles.pan, 0.0);  // turning right, towards 0.15
  EXPECT_GT(robot.trueX(), 0.0);               // driven forward
  robot.shutdown();
  std::ifstream in(path);
  std::string line;
  int lines = 0;
  while (std::getline(in, line))
    ++lines;
  EXPECT_EQ(lines, 60);
  std::filesystem::remove(path);
}

TEST(RobotStage, StopRequestLatchesTheEmergencyStopAndSendsNothingMore) {
  hw::SimulatedRobot robot;
  std::atomic<bool> stop{true};  // Ctrl-C before the first frame
  RobotStageOptions options{&robot.head(), &robot.base(), nullptr, nullptr};
  options.emergencyStop = &stop;
  auto stage = makeRobotStage(options);
  Frame f;
  decide(f);
  stage->process(f);
  EXPECT_TRUE(robot.base().emergencyStopped());
  ASSERT_TRUE(f.robot);
  EXPECT_FALSE(robot.sample().baseCommanded.has_value());  // the drive was never sent
  robot.shutdown();
}

TEST(RobotStage, ALogNeedsItsTelemetrySource) {
  const auto path = std::filesystem::temp_directory_path() / "horopter_robot_stage_bad.jsonl";
  hw::TelemetryLog log(path.string());
  EXPECT_THROW(makeRobotStage({nullptr, nullptr, nullptr, &log}), Error);
  std::filesystem::remove(path);
}

TEST(RobotStage, OverlayDrawsOnBgrOnly) {
  RobotState state;
  state.telemetry.baseSent = {0.2, 0.1};
  cv::Mat bgr(240, 320, CV_8UC3, cv::Scalar::all(0));
  drawRobotOverlay(bgr, state);
  EXPECT_GT(cv::countNonZero(bgr.reshape(1)), 0);
  cv::Mat grey(240, 320, CV_8UC1, cv::Scalar::all(0));
  EXPECT_THROW(drawRobotOverlay(grey, state), Error);
}

}  // namespace
}  // namespace horopter
