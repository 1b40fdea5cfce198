// ROS camera_info YAML files (camera_calibration, camera_info_manager): one
// file per camera, image_width, image_height, camera_name, camera_matrix,
// distortion_model, distortion_coefficients, rectification_matrix and
// projection_matrix, each matrix a map {rows, cols, data}. A stereo pair's
// extrinsics are in the rectification: X_rect = R_i X_i for camera i, and the
// right projection P2 = K' [I | t] places the right rectified camera at t
// (t_x = P2(0,3) / f' = -baseline) in the left rectified frame. So
// X2 = R2^T (R1 X1 + t): R = R2^T R1, T = R2^T t.
#include <array>
#include <charconv>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <sstream>
#include <string>

#include "calibration/calibration_formats.hpp"
#include "file_output.hpp"
#include "horopter/core/error.hpp"

namespace horopter {

namespace detail {

namespace {

// The coefficients a ROS distortion model takes, checked against the file.
cv::Mat distortionFor(const CalibrationStorage& in, const std::string& model, cv::Mat d) {
  const int n = static_cast<int>(d.total());
  if (model == "equidistant" || model == "fisheye")
    in.fail("distortion_model",
            "is '" + model +
                "' (fisheye), which Horopter cannot represent: it rectifies with OpenCV's pinhole "
                "models (plumb_bob, rational_polynomial); calibrate the cameras with one of those");
  if (model == "plumb_bob") {
    if (n == 0) return cv::Mat::zeros(1, 5, CV_64F);  // ROS's "no distortion"
    if (n != 4 && n != 5)
      in.fail("distortion_coefficients",
              "has " + std::to_string(n) + " coefficients; plumb_bob takes 5 (k1 k2 p1 p2 k3)");
    return d;
  }
  if (model == "rational_polynomial") {
    if (n != 8)
      in.fail("distortion_coefficients",
              "has " + std::to_string(n) +
                  " coefficients; rational_polynomial takes 8 (k1 k2 p1 p2 k3 k4 k5 k6)");
    return d;
  }
  in.fail("distortion_model", "is '" + model +
                                  "', which Horopter cannot represent: it takes plumb_bob or "
                                  "rational_polynomial");
}

cv::Vec3d translationOf(const cv::Mat& p) {
  const cv::Matx33d k(p(cv::Rect(0, 0, 3, 3)));
  return k.inv() * cv::Vec3d(p.at<double>(0, 3), p.at<double>(1, 3), p.at<double>(2, 3));
}

// Shortest decimal text that reads back as the same double.
std::string exact(double v) {
  std::array<char, 32> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), v);
  return std::string(buffer.data(), result.ptr);
}

void writeMatrix(std::ostringstream& out, const char* name, const cv::Mat& m) {
  out << name << ":\n  rows: " << m.rows << "\n  cols: " << m.cols << "\n  data: [";
  const cv::Mat d = m.isContinuous() ? m : m.clone();
  for (std::size_t i = 0; i < d.total(); ++i)
    out << (i ? ", " : "") << exact(d.ptr<double>()[i]);
  out << "]\n";
}

// The ROS model for OpenCV's coefficients, and the coefficients it keeps.
std::pair<std::string, cv::Mat> rosDistortion(const cv::Mat& d, const char* name) {
  const int n = static_cast<int>(d.total());
  const cv::Mat row = d.reshape(1, 1);
  if (n == 4 || n == 5) {
    cv::Mat five = cv::Mat::zeros(1, 5, CV_64F);
    row.copyTo(five(cv::Rect(0, 0, n, 1)));
    return {"plumb_bob", five};
  }
  if (n == 8 || ((n == 12 || n == 14) && cv::countNonZero(row(cv::Rect(8, 0, n - 8, 1))) == 0))
    return {"rational_polynomial", row(cv::Rect(0, 0, 8, 1)).clone()};
  std::ostringstream message;
  message << "cannot write ROS camera_info: " << name << " has " << n
          << " distortion coefficients (thin prism or tilt terms), which ROS's plumb_bob and "
             "rational_polynomial models cannot hold";
  throw Error(message.str());
}

std::string cameraInfoText(const StereoCalibration& c, const std::string& name, const cv::Mat& k,
                           const cv::Mat& d, const cv::Mat& r, const cv::Mat& p,
                           const char* distortionName) {
  const auto [model, coefficients] = rosDistortion(d, distortionName);
  std::ostringstream out;
  out << "image_width: " << c.imageSize.width << "\nimage_height: " << c.imageSize.height
      << "\ncamera_name: " << name << "\n";
  writeMatrix(out, "camera_matrix", k);
  out << "distortion_model: " << model << "\n";
  writeMatrix(out, "distortion_coefficients", coefficients);
  writeMatrix(out, "rectification_matrix", r);
  writeMatrix(out, "projection_matrix", p);
  return out.str();
}

}  // namespace

RosCameraInfo readRosCameraInfo(CalibrationStorage& in) {
  in.setAdvice("fix the camera_info file or export it again from ROS");
  RosCameraInfo info;
  info.source = in.path();
  info.imageSize = {in.integer("image_width"), in.integer("image_height")};
  // Only shown, never required: a name YAML reads as a number is let be.
  if (in.get("camera_name").isString()) info.cameraName = in.text("camera_name");
  info.K = in.rosMatrix("camera_matrix", 3, 3);
  const cv::Mat d = in.rosMatrix("distortion_coefficients", 1, 0);
  // Older files have no distortion_model: the count tells the model.
  const std::string model = in.has("distortion_model") ? in.text("distortion_model")
                            : d.total() == 8           ? "rational_polynomial"
                                                       : "plumb_bob";
  info.D = distortionFor(in, model, d);
  info.R = in.rosMatrix("rectification_matrix", 3, 3);
  info.P = in.rosMatrix("projection_matrix", 3, 4);
  const cv::Matx33d kp(info.P(cv::Rect(0, 0, 3, 3)));
  if (!(kp(0, 0) > 0 && kp(1, 1) > 0 && kp(2, 2) == 1))
    in.fail("projection_matrix", "has no positive focal lengths and 1 at (2,2)");
  return info;
}

StereoCalibration stereoFromRos(const RosCameraInfo& left, const RosCameraInfo& right) {
  const std::string pair = "ROS camera_info pair '" + left.source + "' + '" + right.source + "'";
  if (left.imageSize != right.imageSize) {
    std::ostringstream message;
    message << pair << ": the left image is " << left.imageSize.width << "x"
            << left.imageSize.height << " but the right one " << right.imageSize.width << "x"
            << right.imageSize.height << " (image_width, image_height must agree)";
    throw Error(message.str());
  }
  const cv::Vec3d t1 = translationOf(left.P), t2 = translationOf(right.P);
  if (std::abs(t1[0]) > 1e-12 || std::abs(t1[1]) > 1e-12) {
    std::ostringstream message;
    message << pair << ": the left projection_matrix has Tx = " << left.P.at<double>(0, 3)
            << "; ROS puts Tx = 0 in the left camera's file: are left and right swapped?";
    throw Error(message.str());
  }
  const cv::Vec3d t = t2 - t1;
  if (cv::norm(t) > 0 && std::abs(t[0]) < std::abs(t[1])) {
    std::ostringstream message;
    message << pair << ": the projection matrices place the right camera above or below the "
            << "left one (t = " << t[0] << ", " << t[1] << ", " << t[2]
            << "); Horopter needs the cameras side by side (horizontal baseline)";
    throw Error(message.str());
  }
  if (cv::norm(t) == 0)
    throw Error(pair +
                ": the right projection_matrix has Tx = 0, so the files give no baseline (no "
                "T): they hold each camera's intrinsics only. Calibrate the pair as a stereo "
                "pair (ROS camera_calibration with both cameras, or horopter calibrate)");
  StereoCalibration c;
  c.format = "ros camera_info";
  c.imageSize = left.imageSize;
  c.K1 = left.K.clone();
  c.D1 = left.D.clone();
  c.K2 = right.K.clone();
  c.D2 = right.D.clone();
  c.R1 = left.R.clone();
  c.R2 = right.R.clone();
  c.P1 = left.P.clone();
  c.P2 = right.P.clone();
  c.R = c.R2.t() * c.R1;
  c.T = c.R2.t() * cv::Mat(t);
  // Q as cv::stereoRectify builds it for a horizontal pair (t along x).
  const double f = c.P1.at<double>(0, 0), cx1 = c.P1.at<double>(0, 2);
  const double cy = c.P1.at<double>(1, 2), cx2 = c.P2.at<double>(0, 2);
  c.Q = (cv::Mat_<double>(4, 4) << 1, 0, 0, -cx1, 0, 1, 0, -cy, 0, 0, 0, f, 0, 0, -1.0 / t[0],
         (cx1 - cx2) / t[0]);
  // ROS gives no valid regions: the whole image.
  c.roi1 = c.roi2 = cv::Rect({0, 0}, c.imageSize);
  computeEssentialAndFundamental(c);
  return c;
}

}  // namespace detail

void writeRosCameraInfo(const StereoCalibration& c, const std::string& leftPath,
                        const std::string& rightPath, const std::string& cameraName) {
  // A plain name: the file's YAML writes it unquoted.
  const bool plain =
      !cameraName.empty() && cameraName.find_first_not_of(
                                 "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                 "0123456789_-./") == std::string::npos;
  if (!plain)
    throw Error("camera name '" + cameraName +
                "' for ROS camera_info: use letters, digits and _ - . / only");
  if (c.K1.empty() || c.P1.empty() || c.P2.empty() || c.R1.empty() || c.R2.empty())
    throw Error("cannot write ROS camera_info: the calibration has no rectification (R1, P1...)");
  // Both texts before either file: a refused distortion model writes nothing.
  const std::string left =
      detail::cameraInfoText(c, cameraName + "/left", c.K1, c.D1, c.R1, c.P1, "D1");
  const std::string right =
      detail::cameraInfoText(c, cameraName + "/right", c.K2, c.D2, c.R2, c.P2, "D2");
  detail::writeFile(leftPath, left, "ROS camera_info file");
  detail::writeFile(rightPath, right, "ROS camera_info file");
}

}  // namespace horopter
