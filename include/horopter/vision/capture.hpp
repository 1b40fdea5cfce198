// Capture sources for the frame pipeline: a folder of left/right images, a
// pair of video files, two V4L2 cameras, one side-by-side stereo camera.
// (The synthetic scene is the simulator's: horopter/sim/synthetic_source.hpp.)
#pragma once

#include "horopter/core/export.hpp"

#include <memory>
#include <string>

#include "horopter/vision/stereo_frame.hpp"

namespace horopter {

// A camera pair or a recording: fills a frame's left and right images. The
// application runs one as a pipeline's source (frameSourceOf in
// horopter/app/frame.hpp).
class HOROPTER_API StereoSource {
 public:
  virtual ~StereoSource();
  virtual std::string name() const = 0;
  // Fills frame.left and frame.right; false at the end of the input. May
  // block; throws horopter::Error for a device that fails or stalls.
  virtual bool next(StereoFrame& frame) = 0;
};

struct HOROPTER_API CaptureOptions {
  // Cameras: requested size and rate (0: the driver's default).
  int width = 0, height = 0;
  double fps = 0;
  // Two cameras: the most their frames' timestamps may differ to be a pair.
  double maxSkewMs = 15;
  // A camera that delivers nothing for this long ends the run with an error.
  double stallTimeoutMs = 2000;
};

// Opens a source from a spec:
//   dir:PATH                  PATH/left*.{png,jpg,...} with PATH/right*.* (same count,
//                             paired in sorted order), or PATH/left/ and PATH/right/
//   video:LEFT,RIGHT          two video files, frame by frame
//   camera:LEFTDEV,RIGHTDEV   two V4L2 cameras (/dev/video0,/dev/video2), paired by time
//   sbs:DEV                   one side-by-side stereo camera (left half, right half)
// Throws horopter::Error for an unknown spec ("synthetic" is the simulator's:
// a pipeline opens it through sim::syntheticSourceOpener), a missing file or
// device.
HOROPTER_API std::unique_ptr<StereoSource> openSource(const std::string& spec,
                                                      const CaptureOptions& options);

}  // namespace horopter
