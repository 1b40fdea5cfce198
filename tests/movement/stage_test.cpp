// The movement stage: Frame::movement filled every frame, decisions on a
// synthetic sequence, Table II actions started, a base command each frame,
// and the overlay drawn.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "horopter/app/interaction_stages.hpp"
#include "horopter/core/error.hpp"
#include "horopter/eval/movement_training.hpp"
#include "horopter/hardware/base.hpp"
#include "horopter/movement/movement.hpp"

namespace horopter {
namespace {

std::shared_ptr<const MovementModel> smallModel() {
  TrainingOptions o;
  o.sequences = 40;
  return std::make_shared<const MovementModel>(trainMovementModel(o));
}

// Counts the commands a stage sends.
class CountingBase final : public hw::Base {
 public:
  std::string name() const override { return "counting"; }
  void command(const hw::BaseVelocity& v) override {
    ++commands;
    last = v;
  }
  void emergencyStop() override {}
  void releaseEmergencyStop() override {}
  bool emergencyStopped() const override { return false; }
  std::optional<hw::Odometry> odometry() const override { return std::nullopt; }
  int commands = 0;
  hw::BaseVelocity last;
};

TEST(MovementStage, FillsEveryFrameDecidesAndCommandsTheBaseEachFrame) {
  CountingBase base;
  MovementStageOptions options;
  options.base = &base;
  auto stage = makeMovementStage(smallModel(), options);
  EXPECT_EQ(stage->name(), "movement");
  const LabelledSequence seq = syntheticSequence(kTuningSeedBase + 900);
  Frame frame;
  int decisions = 0, right = 0, started = 0;
  for (std::size_t i = 0; i < seq.samples.size(); ++i) {
    frame.body = seq.samples[i];
    stage->process(frame);
    ASSERT_TRUE(frame.movement);
    double sum = 0;
    for (double p : frame.movement->posterior)
      sum += p;
    ASSERT_NEAR(sum, 1.0, 1e-9);
    if (frame.movement->decision) {
      ++decisions;
      right += *frame.movement->decision == seq.labels[i] ? 1 : 0;
    }
    started += frame.movement->actionStarted ? 1 : 0;
  }
  EXPECT_EQ(base.commands, static_cast<int>(seq.samples.size()));
  EXPECT_GE(decisions, 4);
  EXPECT_GE(right, decisions - 1);
  EXPECT_GE(started, 1);
}

TEST(MovementStage, ClassifyTrackGivesOneStatePerSample) {
  const LabelledSequence seq = syntheticSequence(kTuningSeedBase + 901);
  const auto states = classifyTrack(seq.samples, smallModel());
  EXPECT_EQ(states.size(), seq.samples.size());
}

TEST(MovementStage, NoModelIsAnError) {
  EXPECT_THROW(makeMovementStage(nullptr), Error);
}

TEST(MovementOverlay, DrawsIntoTheTopRightCornerOnly) {
  cv::Mat image(480, 640, CV_8UC3, cv::Scalar(200, 200, 200));
  MovementState state;
  state.posterior.fill(1.0 / kMovementClassCount);
  state.likeliest = MovementClass::Circle;
  state.action = RobotAction::Rotate360;
  const cv::Mat before = image.clone();
  drawMovementOverlay(image, state);
  auto changed = [&](cv::Rect r) {
    cv::Mat diff;
    cv::absdiff(image(r), before(r), diff);
    return cv::countNonZero(diff.reshape(1));
  };
  EXPECT_GT(changed(cv::Rect(440, 0, 200, 60)), 0);
  EXPECT_EQ(changed(cv::Rect(0, 200, 400, 280)), 0);
  cv::Mat grey(10, 10, CV_8UC1, cv::Scalar(7));
  drawMovementOverlay(grey, state);  // not BGR: left alone
  EXPECT_EQ(cv::countNonZero(grey != 7), 0);
}

}  // namespace
}  // namespace horopter
