// Where a pipeline's rectification and zone come from, as in `horopter run`:
// a calibration file (maps once, a fixation straight ahead), the synthetic
// scene (its rig and the head's vergence at each frame), or a source that is
// rectified already (the fixation's disparity on the centre column).
#pragma once

#include <optional>
#include <string>

#include "horopter/geometry.hpp"
#include "horopter/pipeline.hpp"
#include "horopter/stereo_params.hpp"
#include "horopter/vision_stages.hpp"

namespace horopter::python {

struct ZoneOptions {
  std::string calib;                        // calibration file, or empty
  double fixation = 1.5;                    // with calib: distance straight ahead
  std::optional<double> fixationDisparity;  // without: px (default: middle of the range)
  std::optional<double> focalPx;            // without: px (default: image width)
};

struct ZoneSetup {
  RectifyFunction rectify;  // empty: the source is rectified already
  ThresholdFunction thresholds;
  RectifiedGeometry rig;        // for the tracker's 3-D points; focalPx 0 when unknown
  double framesPerSecond = 30;  // the tracker's clock for recorded input
};

// Throws horopter::Error for a bad file or a fixation behind the cameras.
ZoneSetup zoneSetup(FrameSource& source, const ZoneOptions& zone, const StereoParams& stereo);

}  // namespace horopter::python
