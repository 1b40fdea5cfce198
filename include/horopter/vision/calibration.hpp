// Stereo calibration of two monocular cameras from chessboard views (Zhang's
// method through OpenCV's calib3d), rectification, and the calibration file.
//
// Units: pixels for image quantities; the board's square size sets the unit
// of every length (T, P2, Q, baseline): give it in metres to get metres.
// Conventions are OpenCV's: a point X1 in the left camera frame is
// X2 = R X1 + T in the right camera frame; rectification uses
// CALIB_ZERO_DISPARITY, so both rectified cameras share the principal point
// and a left pixel (u, v) with disparity d matches the right pixel (u - d, v).
#pragma once

#include "horopter/core/export.hpp"

#include <functional>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "horopter/vision/geometry.hpp"

namespace horopter {

// A chessboard by its inner corners (9x6 for OpenCV's sample views).
struct HOROPTER_API BoardSpec {
  cv::Size innerCorners;    // corners per row (width) and per column (height), each >= 2
  double squareSize = 0.0;  // side of one square, in the length unit of the results (> 0)
};

// "9x6" -> {9, 6}. Throws horopter::Error naming the expected form.
HOROPTER_API cv::Size parseBoardSize(const std::string& text);

struct HOROPTER_API StereoImagePair {
  std::string name;  // shown in progress lines and errors, e.g. "left01.jpg + right01.jpg"
  cv::Mat left;      // 8-bit grey or BGR
  cv::Mat right;
};

// The board's inner corners in one image, refined to sub-pixel accuracy
// (cornerSubPix, 11x11 window), in OpenCV's row-major order; empty when the
// whole board is not found.
HOROPTER_API std::vector<cv::Point2f> findBoardCorners(const cv::Mat& image, cv::Size innerCorners);

struct HOROPTER_API BoardView {
  std::string name;
  std::vector<cv::Point2f> left, right;  // the same corners in both images
};

struct HOROPTER_API BoardDetections {
  cv::Size imageSize;                // the size most pairs have
  std::vector<BoardView> views;      // pairs where the board was found in both images
  std::vector<std::string> skipped;  // "NAME: why", in input order
};

using ProgressFn = std::function<void(const std::string& line)>;

// Finds the board in every pair. A pair is skipped, and named with the reason
// in `skipped`, when either image misses the board, is empty, or differs in
// size from its partner or from the size most pairs have (imageSize).
HOROPTER_API BoardDetections detectBoards(const std::vector<StereoImagePair>& pairs,
                                          cv::Size innerCorners, const ProgressFn& progress = {});

struct HOROPTER_API CalibrationOptions {
  int minViews = 5;    // pairs with the board in both images needed to calibrate (>= 3)
  double alpha = 0.0;  // stereoRectify's free scaling: 0 = only valid pixels, 1 = all pixels
};

struct HOROPTER_API ViewError {
  std::string name;
  double left = 0, right = 0;  // RMS reprojection error of this view per camera, px
};

struct HOROPTER_API StereoCalibration {
  cv::Size imageSize;
  BoardSpec board;  // 0x0 and 0 where the calibration was imported (no board known)
  // Where it came from: "horopter" (calibrateStereo), else the imported
  // format: "opencv" (a stereoCalibrate-style file), "opencv stereo_calib"
  // (intrinsics.yml + extrinsics.yml), "ros camera_info" (a left/right pair).
  std::string format = "horopter";
  cv::Mat K1, D1, K2, D2;     // intrinsics (3x3) and distortion (1xN) per camera
  cv::Mat R, T, E, F;         // extrinsics (3x3, 3x1), essential and fundamental matrices
  cv::Mat R1, R2, P1, P2, Q;  // rectification (3x3, 3x3, 3x4, 3x4, 4x4)
  cv::Rect roi1, roi2;        // valid pixels of each rectified image
  double alpha = 0.0;

  // Quality figures, from the views the calibration used (0 and empty for
  // an imported calibration).
  double rms = 0;                    // stereo RMS reprojection error, px
  double rmsLeft = 0, rmsRight = 0;  // per-camera RMS of the monocular calibrations, px
  double epipolarError = 0;      // mean |y_left - y_right| of the corners after rectification, px
  std::vector<ViewError> views;  // per-view errors of the stereo calibration
  std::vector<std::string> skipped;

  // The board plane's homography from undistorted left pixels to undistorted
  // right pixels, per view: H = K2 (R + T n^T / d) K1^-1, where n^T X = d is
  // the board plane in the left camera frame. homographyError: mean transfer
  // error of the board corners through H, px.
  std::vector<cv::Mat> boardHomographies;
  double homographyError = 0;
};

// Monocular calibration of each camera, then stereoCalibrate refining both
// (intrinsic guess), stereoRectify (CALIB_ZERO_DISPARITY) and the quality
// figures. Throws horopter::Error when fewer than options.minViews views
// remain, naming the skipped ones, or for a non-positive square size.
HOROPTER_API StereoCalibration calibrateStereo(const BoardDetections& detections,
                                               const BoardSpec& board,
                                               const CalibrationOptions& options = {});

// Horopter's calibration file: OpenCV FileStorage (YAML or XML by the
// file's extension). The board and the quality figures are written when the
// calibration has them.
HOROPTER_API void saveStereoCalibration(const StereoCalibration& calibration,
                                        const std::string& path);

// What loadStereoCalibration needs beyond the file for formats that lack it.
struct HOROPTER_API CalibrationImport {
  // The second file of a pair: the right camera's ROS camera_info, or the
  // stereo_calib sample's extrinsics.yml. Empty: found by name next to the
  // first (left.yaml -> right.yaml, intrinsics.yml -> extrinsics.yml).
  std::string right;
  // The image size where the files give none (the stereo_calib pair); where
  // they give one, the two must agree. Empty: the files' own.
  cv::Size imageSize;
  // stereoRectify's free scaling where the files give no R1, R2, P1, P2, Q.
  double alpha = 0.0;
};

// Reads a stereo calibration, its format recognised by content (see
// docs/calibration.md): Horopter's file; an OpenCV file with K1 (or M1), D1,
// K2, D2, R, T and the image size, with or without R1, R2, P1, P2, Q; the
// stereo_calib sample's intrinsics.yml + extrinsics.yml; a ROS camera_info
// pair (left and right YAML). `path` may also be a folder holding left.yaml
// and right.yaml, or intrinsics.yml and extrinsics.yml. Missing
// rectification is computed by cv::stereoRectify as calibrateStereo does;
// every calibration is checked for meaning. Throws horopter::Error naming
// the file and the missing or malformed field.
HOROPTER_API StereoCalibration loadStereoCalibration(const std::string& path,
                                                     const CalibrationImport& import = {});

// Writes one ROS camera_info YAML file per camera, as ROS's
// camera_calibration writes them (camera_name NAME/left and NAME/right;
// plumb_bob for 4 or 5 distortion coefficients, rational_polynomial for 8,
// or for 12 or 14 whose coefficients past the eighth are 0; others cannot be
// written and throw). Every number is written to round trip exactly.
HOROPTER_API void writeRosCameraInfo(const StereoCalibration& calibration,
                                     const std::string& leftPath, const std::string& rightPath,
                                     const std::string& cameraName = "stereo");

// The rectified pair's geometry: f = P1(0,0), cx = P1(0,2), cy = P1(1,2),
// baseline = -P2(0,3) / P2(0,0) (in the board's unit). Throws for a vertical
// or degenerate rectification.
HOROPTER_API RectifiedGeometry rectifiedGeometry(const StereoCalibration& calibration);

// The optical axes of the two (unrectified) cameras in the rectified
// cyclopean frame: origins at the camera centres, directions R1 e_z and R2 e_z.
HOROPTER_API std::pair<Ray, Ray> opticalAxes(const StereoCalibration& calibration);

// The rectification stage of a pipeline: the undistort-rectify maps are
// computed once (initUndistortRectifyMap, fixed-point CV_16SC2), then each
// frame is remapped (bilinear) into buffers owned by the stage and reused.
class HOROPTER_API StereoRectifier {
 public:
  explicit StereoRectifier(const StereoCalibration& calibration);

  // Throws horopter::Error when an image's size differs from the calibration's.
  void rectify(const cv::Mat& left, const cv::Mat& right);
  const cv::Mat& left() const { return outLeft_; }
  const cv::Mat& right() const { return outRight_; }
  cv::Size imageSize() const { return size_; }

 private:
  cv::Size size_;
  cv::Mat map1Left_, map2Left_, map1Right_, map2Right_;
  cv::Mat outLeft_, outRight_;
};

}  // namespace horopter
