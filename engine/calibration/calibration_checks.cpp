#include "calibration/calibration_checks.hpp"

#include <cmath>
#include <opencv2/core.hpp>
#include <sstream>

#include "horopter/core/error.hpp"

namespace horopter {

namespace {

// The pieces streamed into one string (GCC 12 warns falsely, -Wrestrict,
// on long chains of std::string operator+).
template <class... Parts>
std::string text(const Parts&... parts) {
  std::ostringstream out;
  (out << ... << parts);
  return out.str();
}

class Checker {
 public:
  explicit Checker(const std::string& source) : source_(source) {}

  void require(bool ok, const std::string& field, const std::string& what) const {
    if (!ok)
      throw Error(text("calibration '", source_, "': ", field, " ", what,
                       "; re-run horopter calibrate, or fix the file"));
  }

  void cameraMatrix(const cv::Mat& K, const std::string& name, cv::Size image) const {
    require(K.rows == 3 && K.cols == 3 && K.type() == CV_64F, name, "is not a 3x3 matrix");
    const double fx = K.at<double>(0, 0), fy = K.at<double>(1, 1);
    const double cx = K.at<double>(0, 2), cy = K.at<double>(1, 2);
    require(fx > 0 && fy > 0 && std::isfinite(fx) && std::isfinite(fy), name,
            text("has a focal length that is not positive (fx ", fx, ", fy ", fy, ")"));
    require(cx >= 0 && cx <= image.width && cy >= 0 && cy <= image.height, name,
            text("puts the principal point (", cx, ", ", cy, ") outside the ", image.width, "x",
                 image.height, " image"));
    require(K.at<double>(1, 0) == 0 && K.at<double>(2, 0) == 0 && K.at<double>(2, 1) == 0 &&
                K.at<double>(2, 2) == 1,
            name, "is not a camera matrix (its last row must be 0 0 1, K(1,0) 0)");
  }

  void distortion(const cv::Mat& D, const std::string& name) const {
    const int n = static_cast<int>(D.total());
    require(D.rows == 1 && (n == 4 || n == 5 || n == 8 || n == 12 || n == 14), name,
            text("has ", n, " coefficients; OpenCV's models take 4, 5, 8, 12 or 14 in one row"));
  }

  void rotation(const cv::Mat& R, const std::string& name) const {
    require(R.rows == 3 && R.cols == 3 && R.type() == CV_64F, name, "is not a 3x3 matrix");
    const double offOrthonormal = cv::norm(R.t() * R - cv::Mat::eye(3, 3, CV_64F), cv::NORM_INF);
    require(offOrthonormal < 1e-3, name,
            text("is not a rotation (R^T R differs from I by ", offOrthonormal, ")"));
    require(cv::determinant(R) > 0, name, "is a reflection (determinant -1), not a rotation");
  }

  void roi(const cv::Rect& r, const std::string& name, cv::Size image) const {
    require(r.x >= 0 && r.y >= 0 && r.width >= 0 && r.height >= 0 &&
                r.x + static_cast<long long>(r.width) <= image.width &&
                r.y + static_cast<long long>(r.height) <= image.height,
            name,
            text("[", r.x, ", ", r.y, ", ", r.width, ", ", r.height, "] is not inside the image"));
  }

 private:
  const std::string& source_;
};

}  // namespace

void checkCalibration(const StereoCalibration& c, const std::string& source) {
  const Checker check(source);
  const cv::Size image = c.imageSize;
  check.require(image.width > 0 && image.height > 0 && image.width <= kMaxCalibratedSide &&
                    image.height <= kMaxCalibratedSide,
                "image_width x image_height",
                text("is ", image.width, "x", image.height, ", not within 1..", kMaxCalibratedSide,
                     " a side"));
  // An imported calibration knows no board (0x0, square 0): nothing to check.
  const bool board = c.board.innerCorners != cv::Size() || c.board.squareSize != 0;
  if (board) {
    check.require(c.board.squareSize > 0 && std::isfinite(c.board.squareSize), "square_size",
                  text("is ", c.board.squareSize, ", not a positive length"));
    check.require(c.board.innerCorners.width >= 2 && c.board.innerCorners.height >= 2,
                  "board_width x board_height", "must count at least 2x2 inner corners");
  }
  check.cameraMatrix(c.K1, "K1", image);
  check.cameraMatrix(c.K2, "K2", image);
  check.distortion(c.D1, "D1");
  check.distortion(c.D2, "D2");
  check.rotation(c.R, "R");
  check.rotation(c.R1, "R1");
  check.rotation(c.R2, "R2");
  check.require(c.T.total() == 3 && c.T.type() == CV_64F, "T", "is not a 3-vector");
  const double baseline = cv::norm(c.T);
  if (board) {
    const double square = c.board.squareSize;
    check.require(baseline >= 0.01 * square && baseline <= 1e4 * square, "T",
                  text("gives a baseline of ", baseline, " (in the square size's unit, ", square,
                       "): not a stereo rig"));
  } else {
    // No unit to judge the length by: only that there is one.
    check.require(baseline > 0 && std::isfinite(baseline), "T",
                  text("gives a baseline of ", baseline, ": not a stereo rig"));
  }
  check.require(c.P1.rows == 3 && c.P1.cols == 4 && c.P1.at<double>(0, 0) > 0, "P1",
                "has no positive focal length");
  check.require(c.P2.rows == 3 && c.P2.cols == 4 && c.P2.at<double>(0, 0) > 0, "P2",
                "has no positive focal length");
  check.roi(c.roi1, "roi1", image);
  check.roi(c.roi2, "roi2", image);
}

}  // namespace horopter
