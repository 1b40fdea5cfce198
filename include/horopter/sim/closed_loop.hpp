// The simulator's closed loop: the synthetic scene rendered through a
// virtual rig that the head-control stage turns (the view and the zone turn
// with the head). Not part of libhoropter.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>

#include "horopter/app/interaction_stages.hpp"
#include "horopter/hardware/head.hpp"
#include "horopter/interaction/head_control.hpp"
#include "horopter/interaction/tracking.hpp"
#include "horopter/sim/sim_frame.hpp"
#include "horopter/sim/synthetic_scene.hpp"

namespace horopter::sim {

// The synthetic scene's virtual rig as a hw::Head. Two ways in:
//  - post(frame, target): the deterministic path of the head-control stage;
//    the capture of frame M (poseForFrame) waits until every frame up to
//    M - delay has posted, then applies the latest target posted by them.
//  - command(): the hw::Head path (live): the latest target wins and applies
//    at the next frame captured.
class SyntheticRigHead : public hw::Head {
 public:
  SyntheticRigHead(hw::HeadAngles initial, hw::HeadLimits limits, int actuationDelayFrames);
  std::string name() const override { return "synthetic rig"; }
  hw::HeadLimits limits() const override { return limits_; }
  void command(const hw::HeadAngles& target, double speedRadPerS = 0) override;
  std::optional<hw::HeadMeasurement> measured() const override;
  void halt() override;

  // Frames must be posted in increasing order (std::nullopt: no command).
  void post(std::int64_t frame, const std::optional<hw::HeadAngles>& target);
  // The pose to render frame `frame` with; throws horopter::Error when the
  // frames it waits for have not posted within `timeout`.
  hw::HeadAngles poseForFrame(std::int64_t frame,
                              std::chrono::milliseconds timeout = std::chrono::seconds(10));
  int actuationDelayFrames() const { return delay_; }

 private:
  hw::HeadAngles clamp(const hw::HeadAngles& a) const;
  hw::HeadLimits limits_;
  int delay_;
  mutable std::mutex mutex_;
  std::condition_variable posted_;
  std::int64_t postedThrough_ = -1;
  std::deque<std::pair<std::int64_t, hw::HeadAngles>> pending_;
  std::optional<hw::HeadAngles> liveTarget_;
  hw::HeadAngles pose_;
};

// The synthetic scene rendered with the rig's pose for each frame: the view
// turns with the head, and so does the zone (closed loop).
class ClosedLoopSyntheticSource : public FrameSource {
 public:
  // Offline only: capture of frame M waits for the head-control stage's post
  // of frame M - delay, so the pipeline must hold that stage.
  ClosedLoopSyntheticSource(const synth::SceneOptions& options, int frames,
                            int actuationDelayFrames = HeadControlOptions{}.actuationDelayFrames,
                            hw::HeadLimits limits = HeadControlOptions{}.limits);
  std::string name() const override { return "synthetic (closed loop)"; }
  std::unique_ptr<ScheduledFrame> newFrame() override { return std::make_unique<SimFrame>(); }
  bool next(Frame& frame) override;
  synth::SyntheticScene& scene() { return scene_; }
  const std::shared_ptr<SyntheticRigHead>& head() const { return head_; }

 private:
  synth::SyntheticScene scene_;
  std::shared_ptr<SyntheticRigHead> head_;
  int frames_;
  int next_ = 0;
};

// The pose a synthetic frame was rendered with (from its truth).
CapturePose syntheticCapturePose();

// The stage wired to a closed-loop synthetic source.
std::unique_ptr<Stage> makeSyntheticHeadControlStage(HeadControlOptions options,
                                                     ClosedLoopSyntheticSource& source);

}  // namespace horopter::sim
