// Zhang's calibration per camera, then the stereo pair: extrinsics, E and F,
// rectification, the board-plane homographies and the quality figures.
#include <cmath>
#include <numeric>
#include <opencv2/calib3d.hpp>
#include <string>

#include "calibration/calibration_formats.hpp"
#include "horopter/core/error.hpp"
#include "horopter/vision/calibration.hpp"

namespace horopter {

namespace {

std::vector<cv::Point3f> boardPoints(const BoardSpec& board) {
  std::vector<cv::Point3f> points;
  for (int r = 0; r < board.innerCorners.height; ++r)
    for (int c = 0; c < board.innerCorners.width; ++c)
      points.emplace_back(static_cast<float>(c * board.squareSize),
                          static_cast<float>(r * board.squareSize), 0.0f);
  return points;
}

void checkInputs(const BoardDetections& detections, const BoardSpec& board,
                 const CalibrationOptions& options) {
  if (!std::isfinite(board.squareSize) || !(board.squareSize > 0))
    throw Error("square size must be a positive length (e.g. 0.025 for 25 mm squares), got " +
                std::to_string(board.squareSize));
  if (board.innerCorners.width < 2 || board.innerCorners.height < 2)
    throw Error("a board needs at least 2x2 inner corners");
  if (options.minViews < 3)
    throw Error("minViews must be at least 3, got " + std::to_string(options.minViews));
  if (!(options.alpha == -1.0 || (options.alpha >= 0.0 && options.alpha <= 1.0)))
    throw Error("alpha must be in [0, 1] (or -1 for OpenCV's default scaling), got " +
                std::to_string(options.alpha));
  const std::size_t corners =
      static_cast<std::size_t>(board.innerCorners.width) * board.innerCorners.height;
  for (const BoardView& v : detections.views)
    if (v.left.size() != corners || v.right.size() != corners)
      throw Error("view " + v.name + " has " + std::to_string(v.left.size()) + "/" +
                  std::to_string(v.right.size()) + " corners but the board has " +
                  std::to_string(corners));
  if (static_cast<int>(detections.views.size()) < options.minViews) {
    std::string skipped;
    for (const std::string& s : detections.skipped)
      skipped += "\n  skipped " + s;
    throw Error("only " + std::to_string(detections.views.size()) + " of " +
                std::to_string(detections.views.size() + detections.skipped.size()) +
                " views show the whole board in both images; calibration needs at least " +
                std::to_string(options.minViews) +
                ": add views with the whole board visible to both cameras" + skipped);
  }
}

// Mean |y_left - y_right| of the corners after undistortion and rectification.
double rectifiedEpipolarError(const BoardDetections& d, const StereoCalibration& c) {
  double sum = 0;
  std::size_t n = 0;
  for (const BoardView& v : d.views) {
    std::vector<cv::Point2f> l, r;
    cv::undistortPoints(v.left, l, c.K1, c.D1, c.R1, c.P1);
    cv::undistortPoints(v.right, r, c.K2, c.D2, c.R2, c.P2);
    for (std::size_t i = 0; i < l.size(); ++i)
      sum += std::abs(l[i].y - r[i].y);
    n += l.size();
  }
  return sum / static_cast<double>(n);
}

// Per view: the board plane n^T X = dist in the left camera frame (solvePnP),
// H = K2 (R + T n^T / dist) K1^-1 and its transfer error on the corners.
void boardHomographies(const BoardDetections& d, const std::vector<cv::Point3f>& object,
                       StereoCalibration& c) {
  const cv::Matx33d k1(c.K1), k2(c.K2), r(c.R);
  const cv::Vec3d t(c.T);
  double sum = 0;
  std::size_t n = 0;
  for (const BoardView& v : d.views) {
    cv::Vec3d rvec, tvec;
    cv::solvePnP(object, v.left, c.K1, c.D1, rvec, tvec);
    cv::Matx33d rb;
    cv::Rodrigues(rvec, rb);
    const cv::Vec3d normal(rb(0, 2), rb(1, 2), rb(2, 2));
    const double dist = normal.dot(tvec);
    const cv::Matx33d h = k2 * (r + t * normal.t() * (1.0 / dist)) * k1.inv();
    const cv::Matx33d hn = h * (1.0 / h(2, 2));
    c.boardHomographies.push_back(cv::Mat(hn, true));

    std::vector<cv::Point2f> l, rr, mapped;
    cv::undistortPoints(v.left, l, c.K1, c.D1, cv::noArray(), c.K1);
    cv::undistortPoints(v.right, rr, c.K2, c.D2, cv::noArray(), c.K2);
    cv::perspectiveTransform(l, mapped, cv::Matx33f(hn));
    for (std::size_t i = 0; i < l.size(); ++i)
      sum += cv::norm(mapped[i] - rr[i]);
    n += l.size();
  }
  c.homographyError = sum / static_cast<double>(n);
}

}  // namespace

StereoCalibration calibrateStereo(const BoardDetections& detections, const BoardSpec& board,
                                  const CalibrationOptions& options) {
  checkInputs(detections, board, options);
  StereoCalibration c;
  c.imageSize = detections.imageSize;
  c.board = board;
  c.alpha = options.alpha;
  c.skipped = detections.skipped;

  const std::vector<cv::Point3f> object = boardPoints(board);
  std::vector<std::vector<cv::Point3f>> objects(detections.views.size(), object);
  std::vector<std::vector<cv::Point2f>> left, right;
  for (const BoardView& v : detections.views) {
    left.push_back(v.left);
    right.push_back(v.right);
  }
  // Each camera alone first (a good start for the joint refinement).
  std::vector<cv::Mat> rvecs, tvecs;
  c.rmsLeft = cv::calibrateCamera(objects, left, c.imageSize, c.K1, c.D1, rvecs, tvecs);
  c.rmsRight = cv::calibrateCamera(objects, right, c.imageSize, c.K2, c.D2, rvecs, tvecs);

  cv::Mat perView;
  c.rms = cv::stereoCalibrate(
      objects, left, right, c.K1, c.D1, c.K2, c.D2, c.imageSize, c.R, c.T, c.E, c.F, perView,
      cv::CALIB_USE_INTRINSIC_GUESS,
      cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 100, 1e-6));
  if (!std::isfinite(c.rms))
    throw Error(
        "stereo calibration diverged: check that the left and right lists are in the "
        "same order and show the same board poses");
  for (std::size_t i = 0; i < detections.views.size(); ++i)
    c.views.push_back({detections.views[i].name, perView.at<double>(static_cast<int>(i), 0),
                       perView.at<double>(static_cast<int>(i), 1)});

  // The same rectification as for an imported calibration without one.
  detail::computeRectification(c, options.alpha);
  c.epipolarError = rectifiedEpipolarError(detections, c);
  boardHomographies(detections, object, c);
  return c;
}

RectifiedGeometry rectifiedGeometry(const StereoCalibration& c) {
  if (c.P1.size() != cv::Size(4, 3) || c.P2.size() != cv::Size(4, 3))
    throw Error("calibration has no rectified projections P1, P2 (3x4): run horopter calibrate");
  const cv::Matx34d p1(c.P1), p2(c.P2);
  if (std::abs(p2(1, 3)) > 1e-6 * std::abs(p2(0, 3)))
    throw Error(
        "the calibration rectifies a vertical stereo pair; Horopter needs the cameras "
        "side by side (horizontal baseline)");
  RectifiedGeometry g;
  g.focalPx = p1(0, 0);
  g.cx = p1(0, 2);
  g.cy = p1(1, 2);
  g.baseline = -p2(0, 3) / p2(0, 0);
  if (!(g.baseline > 0) || !std::isfinite(g.baseline))
    throw Error("the calibrated right camera is not to the right of the left one (baseline " +
                std::to_string(g.baseline) + "): swap --left and --right");
  if (!(g.focalPx > 0) || !std::isfinite(g.focalPx))
    throw Error("the calibration's rectified focal length is not positive");
  return g;
}

std::pair<Ray, Ray> opticalAxes(const StereoCalibration& c) {
  const RectifiedGeometry g = rectifiedGeometry(c);
  const cv::Matx33d r1(c.R1), r2(c.R2);
  const Ray left{{-0.5 * g.baseline, 0, 0}, {r1(0, 2), r1(1, 2), r1(2, 2)}};
  const Ray right{{0.5 * g.baseline, 0, 0}, {r2(0, 2), r2(1, 2), r2(2, 2)}};
  return {left, right};
}

}  // namespace horopter
