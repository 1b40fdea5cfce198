// Writing the front end's results as image files.
#pragma once

#include <string>

#include <opencv2/core.hpp>

#include "horopter/vision/frontend.hpp"

namespace horopter {

// Colour view of a disparity map: near = hot (red), far = cold (blue),
// invalid = black. The colour scale spans the search range of `params`.
cv::Mat colorizeDisparity(const ConstImageView& disparity, const StereoParams& params);

// Writes `image` to `path` in the format its extension names (.png, .jpg, ...),
// every byte checked. Throws horopter::Error naming `what`, the file and the
// reason (a missing folder, a full disk, an extension OpenCV cannot encode).
void writeImageFile(const std::string& path, const cv::Mat& image,
                    const std::string& what = "image");

// 16-bit PNG in 1/16 px as OpenCV's maps; invalid pixels (and disparities
// <= 0) are written as 0, the usual "unknown".
void writeDisparityPng(const std::string& path, const ConstImageView& disparity,
                       std::int16_t invalid);

// Writes disparity.png, disparity_color.png, and, when the front end has a
// mask, mask.png and segmented.png into `dir` (created if missing). Throws
// horopter::Error if a file cannot be written.
void writeFrontendOutputs(const std::string& dir, const StereoFrontend& frontend);

}  // namespace horopter
