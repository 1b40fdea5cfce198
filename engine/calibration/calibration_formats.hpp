// The calibration formats loadStereoCalibration recognises, each read from
// an opened file into a StereoCalibration (structure only: the caller runs
// checkCalibration), and what they share. See docs/calibration.md.
#pragma once

#include <string>

#include "calibration/calibration_storage.hpp"
#include "horopter/vision/calibration.hpp"

namespace horopter::detail {

// Horopter's own file (horopter_calibration_version), as saveStereoCalibration writes it.
StereoCalibration readHoropterFile(CalibrationStorage& in);

// OpenCV's stereo calibration fields (K1/M1, D1, K2/M2, D2 in `intrinsics`;
// R, T and optionally R1, R2, P1, P2, Q, E, F in `extrinsics`: the same file
// for a stereoCalibrate-style file, two for the stereo_calib sample's
// intrinsics.yml + extrinsics.yml). The image size comes from either file
// or from import.imageSize.
StereoCalibration readOpenCvStereo(CalibrationStorage& intrinsics, CalibrationStorage& extrinsics,
                                   const CalibrationImport& import);

// One camera of a ROS camera_info pair.
struct RosCameraInfo {
  std::string source;  // the file
  std::string cameraName;
  cv::Size imageSize;
  cv::Mat K, D, R, P;  // 3x3, 1xN (OpenCV's order), 3x3, 3x4
};
RosCameraInfo readRosCameraInfo(CalibrationStorage& in);
// The stereo calibration a left/right camera_info pair describes: K, D and
// the rectification (R1 = left R, P1 = left P...) as given; the extrinsics
// R = R2^T R1 and T = R2^T t from the right projection's translation.
StereoCalibration stereoFromRos(const RosCameraInfo& left, const RosCameraInfo& right);

// E and F from R, T and the intrinsics.
void computeEssentialAndFundamental(StereoCalibration& c);
// R1, R2, P1, P2, Q and the ROIs by cv::stereoRectify (CALIB_ZERO_DISPARITY),
// as calibrateStereo computes them.
void computeRectification(StereoCalibration& c, double alpha);

}  // namespace horopter::detail
