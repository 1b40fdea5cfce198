// The application's frame and pipeline: what every stage of Horopter's
// per-frame work reads and fills, run by the generic scheduler
// (horopter/pipeline/scheduler.hpp). buildPipeline() (pipeline_builder.hpp)
// assembles the usual stages; Pipeline, Stage and makeStage are for custom
// ones.
#pragma once

#include "horopter/core/export.hpp"

#include <functional>
#include <memory>
#include <string>

#include "horopter/interaction/body.hpp"
#include "horopter/interaction/detection.hpp"
#include "horopter/interaction/tracking.hpp"
#include "horopter/movement/movement.hpp"
#include "horopter/pipeline/scheduler.hpp"
#include "horopter/vision/capture.hpp"
#include "horopter/vision/stereo_frame.hpp"

namespace horopter {

struct RobotState;  // horopter/app/robot_stage.hpp: what the robot was told and measured

// One frame and everything the stages derive from it. Stages fill the fields
// they produce; later stages read them.
struct HOROPTER_API Frame : StereoFrame {
  std::shared_ptr<const Detections> detections;   // faces, hands, triangles
  std::shared_ptr<const TrackingState> tracking;  // election, tracks, head command
  BodySample body;  // the godfather's head and hands (filled by tracking)
  std::shared_ptr<const MovementState> movement;  // LMA features, posterior, action
  std::shared_ptr<const RobotState> robot;
};

// One step of the per-frame work.
class HOROPTER_API Stage : public ScheduledStage {
 public:
  virtual void process(Frame& frame) = 0;

 private:
  void run(ScheduledFrame& frame) final;
};

// A stage made of a function, for small steps and tests.
HOROPTER_API std::unique_ptr<Stage> makeStage(std::string name, std::function<void(Frame&)> fn);

// A pipeline's source. next() fills the frame's images (a simulator also its
// ground truth, in a frame type of its own that newFrame() makes) and
// returns false at the end of the input.
class HOROPTER_API FrameSource : public ScheduledSource {
 public:
  virtual bool next(Frame& frame) = 0;
  std::unique_ptr<ScheduledFrame> newFrame() override;  // a Frame

 private:
  bool fill(ScheduledFrame& frame) final;
};

// A camera pair or recording (openSource) as a pipeline's source.
HOROPTER_API std::unique_ptr<FrameSource> frameSourceOf(std::unique_ptr<StereoSource> source);

struct HOROPTER_API PipelineOptions {
  PipelineMode mode = PipelineMode::Offline;
  int inFlight = 3;             // frames between capture and the end of the last stage, 1..64
  std::int64_t maxFrames = -1;  // stop after this many captured frames (-1: until the end)
  // Polled by the source loop; set it (e.g. from a SIGINT handler) to stop
  // capture and drain the frames in flight.
  const std::atomic<bool>* stopRequested = nullptr;
  // Called on the last lane with every finished frame, in order of completion
  // (capture order in offline mode). Exceptions count as the "output" stage's.
  std::function<void(const Frame&)> onFrame;
};

// The scheduler with Horopter's frame: see scheduler.hpp for what a run does.
class HOROPTER_API Pipeline {
 public:
  explicit Pipeline(PipelineOptions options);  // validates them (horopter::Error)
  Pipeline& add(std::unique_ptr<Stage> stage);
  const PipelineOptions& options() const { return options_; }
  RunSummary run(FrameSource& source);

 private:
  PipelineOptions options_;
  Scheduler scheduler_;
};

}  // namespace horopter
