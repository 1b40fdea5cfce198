// checkCalibration: a sane calibration passes; each kind of nonsense a file
// can hold (zero or negative focal lengths, a principal point outside the
// image, a wrong number of distortion coefficients, a matrix that is not a
// rotation, a degenerate baseline, a bad square size, ROIs outside the
// image, an absurd image size) is an error naming the field.
#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "calibration/calibration_checks.hpp"
#include "horopter/core/error.hpp"

namespace horopter::test {
namespace {

StereoCalibration sane() {
  StereoCalibration c;
  c.imageSize = {640, 480};
  c.board.innerCorners = {9, 6};
  c.board.squareSize = 0.025;
  c.K1 = (cv::Mat_<double>(3, 3) << 500, 0, 320, 0, 500, 240, 0, 0, 1);
  c.K2 = c.K1.clone();
  c.D1 = cv::Mat::zeros(1, 5, CV_64F);
  c.D2 = cv::Mat::zeros(1, 5, CV_64F);
  c.R = cv::Mat::eye(3, 3, CV_64F);
  c.T = (cv::Mat_<double>(3, 1) << -0.1, 0, 0);
  c.R1 = cv::Mat::eye(3, 3, CV_64F);
  c.R2 = cv::Mat::eye(3, 3, CV_64F);
  c.P1 = (cv::Mat_<double>(3, 4) << 500, 0, 320, 0, 0, 500, 240, 0, 0, 0, 1, 0);
  c.P2 = (cv::Mat_<double>(3, 4) << 500, 0, 320, -50, 0, 500, 240, 0, 0, 0, 1, 0);
  c.roi1 = {10, 10, 600, 450};
  c.roi2 = {0, 0, 640, 480};
  return c;
}

// The check fails, and its message names `field`.
void expectRefused(const std::function<void(StereoCalibration&)>& spoil, const std::string& field) {
  StereoCalibration c = sane();
  spoil(c);
  try {
    checkCalibration(c, "calib.yml");
    ADD_FAILURE() << "accepted a calibration with a bad " << field;
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(field), std::string::npos) << message;
    EXPECT_NE(message.find("calib.yml"), std::string::npos) << message;
  }
}

TEST(CalibrationChecks, ASaneCalibrationPasses) {
  EXPECT_NO_THROW(checkCalibration(sane(), "calib.yml"));
  StereoCalibration eight = sane();
  eight.D2 = cv::Mat::zeros(1, 8, CV_64F);
  EXPECT_NO_THROW(checkCalibration(eight, "calib.yml"));
}

TEST(CalibrationChecks, CameraMatricesMustBeCameraMatrices) {
  expectRefused([](StereoCalibration& c) { c.K1 = cv::Mat::zeros(3, 3, CV_64F); }, "K1");
  expectRefused([](StereoCalibration& c) { c.K2.at<double>(1, 1) = -500; }, "K2");
  expectRefused([](StereoCalibration& c) { c.K1.at<double>(0, 2) = 5000; }, "K1");
  expectRefused([](StereoCalibration& c) { c.K2.at<double>(2, 2) = 0; }, "K2");
}

TEST(CalibrationChecks, DistortionTakesOpenCvsCoefficientCounts) {
  expectRefused([](StereoCalibration& c) { c.D1 = cv::Mat::zeros(1, 3, CV_64F); }, "D1");
  expectRefused([](StereoCalibration& c) { c.D2 = cv::Mat::zeros(1, 6, CV_64F); }, "D2");
}

TEST(CalibrationChecks, RotationsMustBeRotations) {
  expectRefused([](StereoCalibration& c) { c.R = cv::Mat::zeros(3, 3, CV_64F); }, "R ");
  expectRefused([](StereoCalibration& c) { c.R1.at<double>(0, 1) = 0.5; }, "R1");
  expectRefused([](StereoCalibration& c) { c.R2.at<double>(2, 2) = -1; }, "R2");
}

TEST(CalibrationChecks, TheBaselineAndTheBoardMustBePlausible) {
  expectRefused([](StereoCalibration& c) { c.T = (cv::Mat_<double>(3, 1) << 1e-9, 0, 0); }, "T");
  expectRefused([](StereoCalibration& c) { c.T = (cv::Mat_<double>(3, 1) << 1e6, 0, 0); }, "T");
  expectRefused([](StereoCalibration& c) { c.board.squareSize = -0.025; }, "square_size");
  expectRefused([](StereoCalibration& c) { c.board.squareSize = std::nan(""); }, "square_size");
  expectRefused([](StereoCalibration& c) { c.board.innerCorners = {1, 6}; }, "board_width");
}

TEST(CalibrationChecks, AnImportedCalibrationNeedsNoBoard) {
  // No board (0x0, square 0): the board checks are skipped, and the baseline
  // only has to exist (no square to judge its length by).
  StereoCalibration imported = sane();
  imported.board = {};
  imported.T = (cv::Mat_<double>(3, 1) << -120.0, 0, 0);  // millimetres, say
  EXPECT_NO_THROW(checkCalibration(imported, "calib.yml"));
  expectRefused(
      [](StereoCalibration& c) {
        c.board = {};
        c.T = cv::Mat::zeros(3, 1, CV_64F);
      },
      "T");
  // Half a board is not "no board".
  expectRefused([](StereoCalibration& c) { c.board.innerCorners = {}; }, "board_width");
  expectRefused([](StereoCalibration& c) { c.board.squareSize = 0; }, "square_size");
}

TEST(CalibrationChecks, RoisAndTheImageSizeMustFit) {
  expectRefused([](StereoCalibration& c) { c.roi1 = {600, 0, 100, 10}; }, "roi1");
  expectRefused([](StereoCalibration& c) { c.roi2 = {-1, 0, 10, 10}; }, "roi2");
  expectRefused([](StereoCalibration& c) { c.imageSize = {1 << 30, 480}; }, "image_width");
  expectRefused([](StereoCalibration& c) { c.P2.at<double>(0, 0) = 0; }, "P2");
}

}  // namespace
}  // namespace horopter::test
