// One stereo frame as the vision layer sees it: the pair as captured, the
// rectified grey pair, the disparity and the zone of interaction. The
// application's Frame (horopter/app/frame.hpp) adds what the later layers
// derive from it; detection and tracking read only this part.
#pragma once

#include "horopter/core/export.hpp"

#include <opencv2/core.hpp>

#include <cstdint>
#include <vector>

#include "horopter/pipeline/scheduler.hpp"
#include "horopter/vision/zone_search.hpp"

namespace horopter {

struct HOROPTER_API StereoFrame : ScheduledFrame {
  cv::Mat left, right;                   // as captured (BGR or grey)
  cv::Mat leftGrey, rightGrey;           // rectified, grey: the front end's input
  std::vector<std::int16_t> thresholds;  // horopter threshold per column (1/16 px)
  cv::Mat disparity;                     // CV_16SC1, 1/16 px, after cleanup and median
  SearchRange searchRange;               // the disparities the frame's matching searched
  cv::Mat mask;                          // CV_8UC1, 255 inside the zone
};

}  // namespace horopter
