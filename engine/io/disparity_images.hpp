// Writing the front end's results as image files.
#pragma once

#include <string>

#include <opencv2/core.hpp>

#include "horopter/vision/frontend.hpp"

namespace horopter {

// Colour view of a disparity map: near = hot (red), far = cold (blue),
// invalid = black. The colour scale spans the search range of `params`.
cv::Mat colorizeDisparity(const ConstImageView& disparity, const StereoParams& params);
// The same, drawn into `out` (BGR, the disparity's size; a view into a
// larger image, such as a mosaic's panel, saves an image and its copy).
// Throws horopter::Error when `out` is not such an image.
void colorizeDisparityInto(const ConstImageView& disparity, const StereoParams& params,
                           cv::Mat& out);

// The colour scale of colorizeDisparity: a bar in the bottom-right corner of
// `view` (a BGR image) from the search range's lowest disparity (left, blue)
// to its highest (right, red), with both values in px at its ends. Returns
// the rectangle it covers; an empty one (nothing drawn) when the image is
// too small to hold it. disparityScaleRect gives that rectangle alone. On a
// view drawn at 1/shrink of its size, the scale is 1/shrink as large.
cv::Rect disparityScaleRect(cv::Size view, int shrink = 1);
cv::Rect drawDisparityScale(cv::Mat& view, const StereoParams& params, int shrink = 1);

// Writes `image` to `path` in the format its extension names (.png, .jpg, ...),
// every byte checked. Throws horopter::Error naming `what`, the file and the
// reason (a missing folder, a full disk, an extension OpenCV cannot encode).
void writeImageFile(const std::string& path, const cv::Mat& image,
                    const std::string& what = "image");

// 16-bit PNG in 1/16 px as OpenCV's maps; invalid pixels (and disparities
// <= 0) are written as 0, the usual "unknown". Kept for the readers that
// expect it; disparity16.png and disparity.pfm keep the negative ones.
void writeDisparityPng(const std::string& path, const ConstImageView& disparity,
                       std::int16_t invalid);

// Signed, sub-pixel disparities in a 16-bit PNG ("disparity16.png"): each
// pixel holds d16 + 32768, d16 the disparity in 1/16 px, and 0 means invalid
// (a d16 of -32768 is written as -32767). Decode: d_px = (value - 32768) / 16
// where value != 0. Every int16 disparity but -32768 round-trips exactly.
constexpr int kDisparity16Offset = 32768;
cv::Mat encodeDisparity16(const ConstImageView& disparity, std::int16_t invalid);
void writeDisparity16Png(const std::string& path, const ConstImageView& disparity,
                         std::int16_t invalid);
// Reads a disparity16.png back as CV_16SC1 in 1/16 px, writing `invalid`
// where the file holds 0. Throws horopter::Error naming the file when it is
// missing, not 16-bit single-channel, or not decodable.
cv::Mat readDisparity16Png(const std::string& path, std::int16_t invalid);

// Middlebury's PFM: float32 in px, grey ("Pf"), rows stored bottom to top,
// little-endian (scale -1). writePfm writes a CV_32FC1 image as is;
// writeDisparityPfm converts a 1/16 px disparity map to px with +inf where it
// is invalid, as Middlebury's ground truth marks unknown pixels.
void writePfm(const std::string& path, const cv::Mat& image);
void writeDisparityPfm(const std::string& path, const ConstImageView& disparity,
                       std::int16_t invalid);
// Reads a PFM file ("Pf" grey, or "PF" colour, whose first channel is taken),
// either byte order, into CV_32FC1 top row first; inf and NaN are kept.
// Throws horopter::Error naming the file on a malformed or short file.
cv::Mat readPfm(const std::string& path);
// True if the file at `path` starts with a PFM signature ("Pf" or "PF").
bool isPfmFile(const std::string& path);

// Writes disparity.png, disparity16.png, disparity.pfm, disparity_color.png,
// and, when the front end has a mask, mask.png and segmented.png into `dir`
// (created if missing). Throws horopter::Error if a file cannot be written.
void writeFrontendOutputs(const std::string& dir, const StereoFrontend& frontend);

}  // namespace horopter
