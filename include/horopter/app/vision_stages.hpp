// The front end's stages for the frame pipeline: rectify (to grey), disparity
// (prefilter, matching, cleanup, median) and the horopter mask.
#pragma once

#include "horopter/core/export.hpp"

#include <functional>
#include <memory>
#include <optional>

#include "horopter/app/frame.hpp"
#include "horopter/kernels/backend.hpp"
#include "horopter/kernels/stereo_params.hpp"
#include "horopter/vision/zone_search.hpp"

namespace horopter {

// The zone's thresholds for a frame (one per column of the rectified
// views, 1/16 px): a function of the frame, since the head's pose at
// capture time makes the horopter dynamic. `out` comes sized to the width.
using ThresholdFunction = std::function<void(const Frame& frame, std::vector<std::int16_t>& out)>;

// Grey rectified views for the front end, and the frame's zone. With a
// `rectify` function (maps computed once, e.g. from a calibration), it is
// applied to both captured images first; without one the source is taken
// as rectified already. With `thresholds`, Frame::thresholds is filled
// here, before the disparity, so that the zone can set the search range:
// both are the rig's geometry at capture time.
using RectifyFunction = std::function<void(const cv::Mat& left, const cv::Mat& right,
                                           cv::Mat& leftOut, cv::Mat& rightOut)>;
HOROPTER_API std::unique_ptr<Stage> makeRectifyStage(RectifyFunction rectify = {},
                                                     ThresholdFunction thresholds = {});

// The disparity of Frame::leftGrey/rightGrey (cleaned up, median-filtered)
// into Frame::disparity, on `threads` threads of the stage's own pool. An
// OpenCL backend runs the device-resident OpenClFrontend (with its CPU
// fallback; `threads` are then the fallback's). With zone search on, each
// frame searches zoneSearchRange() of its thresholds (the rectify stage's).
HOROPTER_API std::unique_ptr<Stage> makeDisparityStage(const StereoParams& stereo,
                                                       const MedianParams& median,
                                                       const Backend& backend, int threads,
                                                       const ZoneSearch& zone = {});

// Frame::mask from the disparity and Frame::thresholds (the rectify stage's).
HOROPTER_API std::unique_ptr<Stage> makeMaskStage(const StereoParams& stereo,
                                                  const Backend& backend);

// Thresholds for a source that is rectified already and has no calibration:
// the fixation point is given by its disparity (px) on the centre column
// (default: the middle of the search range) and the focal length (default:
// the image width); thresholds in pixels do not depend on the baseline's
// unit. Throws horopter::Error for a fixation that is not a positive disparity.
HOROPTER_API ThresholdFunction
fixationDisparityThresholds(const StereoParams& stereo, std::optional<double> fixationDisparityPx,
                            std::optional<double> focalPx);

}  // namespace horopter
