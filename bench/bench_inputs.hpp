// The synthetic stereo pair every row runs on: made once per size, outside
// the timed loops, the same on every run (fixed seed).
#pragma once

#include <cstdint>
#include <vector>

#include "bench_support.hpp"
#include "horopter/core/image.hpp"

namespace horopter::bench {

// A rectified pair of smoothed-noise texture. The right view sees a slanted
// background plane, two nearer planes (whose edges leave occlusions for the
// left-right check) and a textureless patch (for the texture check), with
// disparities between 8 and 48 px at every size, plus sensor noise on the
// right view.
struct StereoPair {
  Image left;        // U8C1
  Image right;       // U8C1
  Image leftColour;  // U8C3, the left view as BGR, for segmentation
};

// Fixation disparity (px), about the rectangle's: the disc lies inside the
// horopter circle, the background outside, so the mask has both.
inline constexpr double kFixationDisparityPx = 30;

StereoPair makeStereoPair(FrameSize size);

// Horopter thresholds for the pair: focal length = width and principal point
// at the centre (the CLI's defaults), fixation at kFixationDisparityPx on the
// centre column.
std::vector<std::int16_t> sceneThresholds(FrameSize size);

// The pair of this size, made on first use and kept for the run.
const StereoPair& stereoPair(FrameSize size);

}  // namespace horopter::bench
