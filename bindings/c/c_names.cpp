// The library's messages name the C++ members (`numDisparities`); a C caller
// knows the fields of include/horopter/horopter.h (`num_disparities`). The
// C API rewrites the one into the other before it stores a message.
#include <cctype>
#include <string>
#include <string_view>

#include "guarded.hpp"

namespace horopter::c_api {

namespace {

struct Rename {
  std::string_view cpp, c;
};

// Longer phrases first: "median kernel size (kernelSize)" reads better whole.
constexpr Rename kRenames[] = {
    {"median kernel size (kernelSize)", "median_kernel_size"},
    {"median minValidToFill", "median_min_valid"},
    {"maxDisparity", "min_disparity + num_disparities"},
    {"minDisparity", "min_disparity"},
    {"numDisparities", "num_disparities"},
    {"blockSize", "block_size"},
    {"preFilterType", "pre_filter_type"},
    {"preFilterSize", "pre_filter_size"},
    {"preFilterCap", "pre_filter_cap"},
    {"textureThreshold", "texture_threshold"},
    {"uniquenessRatio", "uniqueness_ratio"},
    {"disp12MaxDiff", "disp12_max_diff"},
    {"speckleWindowSize", "speckle_window_size"},
    {"speckleRange", "speckle_range"},
    {"leftBand", "left_band"},
    {"kernelSize", "median_kernel_size"},
    {"minValidToFill", "median_min_valid"},
    {"inFlight", "in_flight"},
    {"maxFrames", "frames"},
    {"fixationDisparityPx", "fixation_disparity_px"},
    {"focalPx", "focal_px"},
};

bool identifierChar(char ch) {
  return std::isalnum(static_cast<unsigned char>(ch)) != 0 || ch == '_';
}

}  // namespace

std::string inCNames(std::string message) {
  for (const Rename& r : kRenames) {
    std::size_t at = 0;
    while ((at = message.find(r.cpp, at)) != std::string::npos) {
      const std::size_t end = at + r.cpp.size();
      const bool whole = (at == 0 || !identifierChar(message[at - 1])) &&
                         (end == message.size() || !identifierChar(message[end]));
      if (!whole) {
        at = end;
        continue;
      }
      message.replace(at, r.cpp.size(), r.c);
      at += r.c.size();
    }
  }
  return message;
}

}  // namespace horopter::c_api
