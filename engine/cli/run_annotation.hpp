// The annotated view of a frame for `horopter run`: the left image with the
// zone's ROI, the disparity colour map, and the mask over the image.
#pragma once

#include <opencv2/core.hpp>

#include "horopter/app/frame.hpp"
#include "horopter/kernels/stereo_params.hpp"

namespace horopter::cli {

// A 2x2 mosaic (left | disparity / mask overlay | text panel), BGR, twice
// the frame's width and height divided by `shrink` (>= 1; 2 draws a video
// frame of --video-scale 2 directly, at about a third of the cost).
cv::Mat annotateFrame(const Frame& frame, const StereoParams& params, double fps, int shrink = 1);

}  // namespace horopter::cli
