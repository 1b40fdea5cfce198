// The interaction and movement layers' algorithms as pipeline stages.
#include "horopter/app/interaction_stages.hpp"

#include <utility>

#include "horopter/core/error.hpp"

namespace horopter {

namespace {

class DetectionStage final : public Stage {
 public:
  explicit DetectionStage(DetectorOptions options) : detector_(std::move(options)) {}
  std::string name() const override { return "detection"; }
  void process(Frame& frame) override {
    frame.detections = std::make_shared<const Detections>(detector_.detect(frame));
  }

 private:
  Detector detector_;
};

class TrackingStage final : public Stage {
 public:
  explicit TrackingStage(TrackerOptions options) : tracker_(std::move(options)) {}
  std::string name() const override { return "tracking"; }
  void process(Frame& frame) override {
    if (!frame.detections)
      throw Error("tracking needs Frame::detections: run the detection stage first");
    frame.tracking = std::make_shared<const TrackingState>(
        tracker_.update(frame, *frame.detections, frame.body));
  }

 private:
  BodyTracker tracker_;
};

class HeadControlStage final : public Stage {
 public:
  HeadControlStage(HeadControlOptions o, CapturePose pose, HeadCommandSink sink)
      : o_(o), pose_(std::move(pose)), sink_(std::move(sink)) {
    validate(o_);
  }
  std::string name() const override { return "head control"; }
  void process(Frame& frame) override {
    std::optional<hw::HeadAngles> command;
    try {
      command = compute(frame);
    } catch (...) {
      sink_(frame.index, std::nullopt);  // capture must not wait for this frame
      throw;
    }
    sink_(frame.index, command);
    if (command && frame.tracking) {
      auto state = std::make_shared<TrackingState>(*frame.tracking);
      state->headCommand = command;
      state->headCommandFrame = frame.index + o_.actuationDelayFrames;
      frame.tracking = state;
    }
  }

 private:
  std::optional<hw::HeadAngles> compute(const Frame& frame) const {
    if (!frame.tracking)
      throw Error("head control needs Frame::tracking: run the tracking stage first");
    if (!wantsHeadCommand(*frame.tracking)) return std::nullopt;
    const std::optional<hw::HeadAngles> pose = pose_(frame);
    if (!pose) return std::nullopt;
    return headCommand(*frame.tracking, *pose, o_);
  }

  HeadControlOptions o_;
  CapturePose pose_;
  HeadCommandSink sink_;
};

class MovementStage final : public Stage {
 public:
  MovementStage(std::shared_ptr<const MovementModel> model, MovementStageOptions options)
      : analyser_(std::move(model), options) {}
  std::string name() const override { return "movement"; }
  void process(Frame& frame) override {
    frame.movement = std::make_shared<const MovementState>(analyser_.update(frame.body));
  }

 private:
  MovementAnalyser analyser_;
};

}  // namespace

std::unique_ptr<Stage> makeDetectionStage(DetectorOptions options) {
  return std::make_unique<DetectionStage>(std::move(options));
}

std::unique_ptr<Stage> makeTrackingStage(TrackerOptions options) {
  return std::make_unique<TrackingStage>(std::move(options));
}

std::unique_ptr<Stage> makeHeadControlStage(HeadControlOptions options, CapturePose pose,
                                            HeadCommandSink sink) {
  if (!pose) throw Error("head control needs the head's pose at capture");
  if (!sink) throw Error("head control needs somewhere to send its commands");
  return std::make_unique<HeadControlStage>(options, std::move(pose), std::move(sink));
}

std::unique_ptr<Stage> makeMovementStage(std::shared_ptr<const MovementModel> model,
                                         MovementStageOptions options) {
  return std::make_unique<MovementStage>(std::move(model), options);
}

}  // namespace horopter
