// Capture sources for the frame pipeline: the synthetic scene, a folder of
// left/right images, a pair of video files, two V4L2 cameras, one
// side-by-side stereo camera.
#pragma once

#include <memory>
#include <string>

#include "horopter/pipeline.hpp"
#include "horopter/synthetic_scene.hpp"

namespace horopter {

struct CaptureOptions {
  // Cameras: requested size and rate (0: the driver's default).
  int width = 0, height = 0;
  double fps = 0;
  // Two cameras: the most their frames' timestamps may differ to be a pair.
  double maxSkewMs = 15;
  // A camera that delivers nothing for this long ends the run with an error.
  double stallTimeoutMs = 2000;
  // Synthetic scene.
  synth::SceneOptions scene;
  int frames = 300;  // the synthetic scene's length
};

// Opens a source from a spec:
//   synthetic                 the built-in synthetic scene (CaptureOptions::scene)
//   dir:PATH                  PATH/left*.{png,jpg,...} with PATH/right*.* (same count,
//                             paired in sorted order), or PATH/left/ and PATH/right/
//   video:LEFT,RIGHT          two video files, frame by frame
//   camera:LEFTDEV,RIGHTDEV   two V4L2 cameras (/dev/video0,/dev/video2), paired by time
//   sbs:DEV                   one side-by-side stereo camera (left half, right half)
// Throws horopter::Error for an unknown spec, a missing file or device.
std::unique_ptr<FrameSource> openSource(const std::string& spec, const CaptureOptions& options);

// The synthetic source, for the stages that need its scene (head commands,
// ground truth). Each frame's truth is a synth::FrameTruth in Frame::truth.
class SyntheticSource : public FrameSource {
 public:
  SyntheticSource(const synth::SceneOptions& options, int frames);
  std::string name() const override { return "synthetic"; }
  bool next(Frame& frame) override;
  synth::SyntheticScene& scene() { return scene_; }

 private:
  synth::SyntheticScene scene_;
  int frames_;
  int next_ = 0;
};

}  // namespace horopter
