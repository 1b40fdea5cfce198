// The simulator's sources for the frame pipeline: the built-in synthetic
// scene, open loop (SyntheticSource) or turned by the head control
// (ClosedLoopSyntheticSource, horopter/sim/closed_loop.hpp), and the opener
// that hands either to buildPipeline for the spec "synthetic". Not part of
// libhoropter: the CLI, the Python module and the evaluations link it.
#pragma once

#include <memory>
#include <string>

#include "horopter/app/pipeline_builder.hpp"
#include "horopter/app/vision_stages.hpp"
#include "horopter/sim/sim_frame.hpp"
#include "horopter/sim/synthetic_scene.hpp"

namespace horopter::sim {

// The synthetic scene, open loop. Its frames are SimFrames: truthOf() gives
// their synth::FrameTruth.
class SyntheticSource : public FrameSource {
 public:
  SyntheticSource(const synth::SceneOptions& options, int frames);
  std::string name() const override { return "synthetic"; }
  std::unique_ptr<ScheduledFrame> newFrame() override { return std::make_unique<SimFrame>(); }
  bool next(Frame& frame) override;
  synth::SyntheticScene& scene() { return scene_; }

 private:
  synth::SyntheticScene scene_;
  int frames_;
  int next_ = 0;
};

// The zone's thresholds for each frame from the scene's rig and the
// vergence in the frame's truth (the head verges on what it looks at).
ThresholdFunction syntheticZoneThresholds(const synth::SyntheticScene& scene);

struct SyntheticSourceOptions {
  synth::SceneOptions scene;
  int frames = 300;  // the scene's length, 1..
};

// Opens "synthetic" (and nothing else): closed loop when the builder wants
// a steerable source, else open loop; with frames in flight the scene
// renders on the capture thread alone (the other cores take the frames
// ahead). `scene`, if given, is set to the opened scene (it lives as long as
// the pipeline).
SourceOpener syntheticSourceOpener(SyntheticSourceOptions options,
                                   const synth::SyntheticScene** scene = nullptr);

}  // namespace horopter::sim
