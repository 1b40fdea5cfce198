// The godfather's body in one frame, as tracking hands it to movement
// analysis: the contract between detection/tracking (issue 7) and the Laban
// Movement Analysis and classifier (issue 8). Also what a recorded track
// file holds, one sample per frame.
#pragma once

#include "horopter/core/export.hpp"

#include <opencv2/core.hpp>

#include <cstdint>
#include <limits>

namespace horopter {

// One tracked body part.
struct HOROPTER_API PartState {
  bool tracked = false;   // a track exists this frame (it may be coasting)
  bool observed = false;  // a detection updated the track this frame
  cv::Point2f image;      // left rectified image, pixels
  // Rig frame, metres (x right, y down, z forward); NaN where depth is unknown.
  cv::Point3f rig{std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::quiet_NaN(),
                  std::numeric_limits<float>::quiet_NaN()};
};

// Left and right are the person's own (the person faces the robot, so their
// left hand appears on the image's right side).
struct HOROPTER_API BodySample {
  std::int64_t frame = 0;
  double timeS = 0;        // seconds since the start of the run
  bool godfather = false;  // a godfather is elected; the parts below are theirs
  PartState head, leftHand, rightHand;
};

}  // namespace horopter
