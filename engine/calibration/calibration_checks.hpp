// What a calibration must hold before a rectifier is built from it: the
// structure is the file readers' job (calibration_formats.hpp); these are the
// meanings. Each failure throws horopter::Error naming the source, the field
// and what to fix.
#pragma once

#include <string>

#include "horopter/vision/calibration.hpp"

namespace horopter {

// The largest image side a calibration may give: the rectifier allocates
// maps of the image's size before any frame arrives.
inline constexpr int kMaxCalibratedSide = 16384;

// Positive focal lengths and a principal point inside the image; a camera
// matrix with 0 0 1 as its last row; 4, 5, 8, 12 or 14 distortion
// coefficients; orthonormal rotations (R, R1, R2) with determinant +1; a
// positive finite square size and at least 2x2 inner corners, and a
// baseline longer than a hundredth of a square and shorter than 10 000
// squares (where the calibration knows its board: an imported one has no
// board, and then only a positive finite baseline is required);
// ROIs inside the image; an image of at most kMaxCalibratedSide a side.
// `source` names the file in the messages.
void checkCalibration(const StereoCalibration& c, const std::string& source);

}  // namespace horopter
