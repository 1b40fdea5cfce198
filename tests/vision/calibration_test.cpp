// Stereo calibration on OpenCV's chessboard views (opencv-doc's
// left01..14.jpg / right01..14.jpg, 9x6 inner corners; there is no 10), done
// once per test binary, plus the failure paths and the calibration file.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <numbers>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/persistence.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "horopter/core/error.hpp"
#include "horopter/vision/calibration.hpp"
#include "horopter/vision/geometry.hpp"
#include "test_support.hpp"

namespace horopter::test {
namespace {

const cv::Size kBoard(9, 6);
constexpr double kSquare = 0.025;

// The folder holding the views: opencv-doc's examples, else the copy in
// ../shared/data; empty when neither is there.
std::string viewsDir() {
  for (const std::string& dir : {opencvDataDir(), sharedDataDir() + "/opencv_stereo_calib"}) {
    if (isFile(dir + "/left01.jpg") && isFile(dir + "/right01.jpg")) return dir;
  }
  return {};
}

std::vector<StereoImagePair> loadViews(const std::string& dir) {
  std::vector<StereoImagePair> pairs;
  for (int i = 1; i <= 14; ++i) {
    char id[12];  // room for any int: gcc -O1 (the sanitizer builds) cannot bound i
    std::snprintf(id, sizeof id, "%02d", i);
    const std::string l = dir + "/left" + id + ".jpg", r = dir + "/right" + id + ".jpg";
    if (!isFile(l) || !isFile(r)) continue;
    pairs.push_back({std::string("view ") + id, cv::imread(l, cv::IMREAD_GRAYSCALE),
                     cv::imread(r, cv::IMREAD_GRAYSCALE)});
  }
  return pairs;
}

template <typename F>
void expectError(F&& f, const std::vector<std::string>& words) {
  try {
    f();
    ADD_FAILURE() << "no horopter::Error";
  } catch (const Error& e) {
    for (const std::string& w : words)
      EXPECT_NE(std::string(e.what()).find(w), std::string::npos)
          << "\"" << e.what() << "\" does not mention " << w;
  }
}

// Detection and calibration run once for every test of the suite.
class OpenCVViews : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = viewsDir();
    if (dir_.empty()) return;
    std::vector<StereoImagePair> pairs = loadViews(dir_);
    inputViews_ = static_cast<int>(pairs.size());
    // A pair without a board, in the middle: it must be named and skipped.
    const cv::Size size = pairs.front().left.size();
    pairs.insert(pairs.begin() + 3, StereoImagePair{"blank pair", cv::Mat(size, CV_8UC1, 128),
                                                    cv::Mat(size, CV_8UC1, 128)});
    detections_ = std::make_unique<BoardDetections>(detectBoards(pairs, kBoard));
    calibration_ =
        std::make_unique<StereoCalibration>(calibrateStereo(*detections_, {kBoard, kSquare}));
  }
  static void TearDownTestSuite() {
    detections_.reset();
    calibration_.reset();
  }
  void SetUp() override {
    if (dir_.empty())
      GTEST_SKIP() << "OpenCV's stereo chessboard views not found in " << opencvDataDir()
                   << " (Debian package opencv-doc) nor in " << sharedDataDir()
                   << "/opencv_stereo_calib";
  }

  static inline std::string dir_;
  static inline int inputViews_ = 0;
  static inline std::unique_ptr<BoardDetections> detections_;
  static inline std::unique_ptr<StereoCalibration> calibration_;
};

TEST_F(OpenCVViews, FindsTheBoardInEveryPairAndNamesTheSkippedOne) {
  EXPECT_EQ(static_cast<int>(detections_->views.size()), inputViews_);
  ASSERT_EQ(detections_->skipped.size(), 1u);
  EXPECT_NE(detections_->skipped[0].find("blank pair"), std::string::npos);
  EXPECT_NE(detections_->skipped[0].find("no 9x6 board"), std::string::npos);
  for (const BoardView& v : detections_->views) {
    EXPECT_EQ(v.left.size(), 54u) << v.name;
    EXPECT_EQ(v.right.size(), 54u) << v.name;
  }
  EXPECT_EQ(calibration_->skipped, detections_->skipped);
}

TEST_F(OpenCVViews, ReprojectionAndRectifiedEpipolarErrorsAreUnderOnePixel) {
  const StereoCalibration& c = *calibration_;
  RecordProperty("rms", std::to_string(c.rms));
  RecordProperty("epipolar_error", std::to_string(c.epipolarError));
  std::printf(
      "RMS %.4f px (left %.4f, right %.4f), rectified epipolar error %.4f px, "
      "homography transfer %.4f px\n",
      c.rms, c.rmsLeft, c.rmsRight, c.epipolarError, c.homographyError);
  EXPECT_LT(c.rms, 1.0);
  EXPECT_LT(c.rmsLeft, 1.0);
  EXPECT_LT(c.rmsRight, 1.0);
  EXPECT_LT(c.epipolarError, 1.0);
  ASSERT_EQ(static_cast<int>(c.views.size()), inputViews_);
  for (const ViewError& v : c.views) {
    EXPECT_TRUE(v.left > 0 && v.left < 2.0) << v.name << " left " << v.left;
    EXPECT_TRUE(v.right > 0 && v.right < 2.0) << v.name << " right " << v.right;
  }
  // The board-plane homographies carry the left corners onto the right ones.
  EXPECT_EQ(c.boardHomographies.size(), c.views.size());
  EXPECT_LT(c.homographyError, 2.0);
}

TEST_F(OpenCVViews, EpipolarErrorIsMeasuredIndependently) {
  // Recompute |y_l - y_r| after rectification from the stored corners and
  // matrices alone.
  const StereoCalibration& c = *calibration_;
  double sum = 0;
  std::size_t n = 0;
  for (const BoardView& v : detections_->views) {
    std::vector<cv::Point2f> l, r;
    cv::undistortPoints(v.left, l, c.K1, c.D1, c.R1, c.P1);
    cv::undistortPoints(v.right, r, c.K2, c.D2, c.R2, c.P2);
    for (std::size_t i = 0; i < l.size(); ++i)
      sum += std::abs(l[i].y - r[i].y);
    n += l.size();
  }
  EXPECT_NEAR(sum / n, c.epipolarError, 1e-9);
}

TEST_F(OpenCVViews, RectifiedGeometryIsAHorizontalPair) {
  const RectifiedGeometry g = rectifiedGeometry(*calibration_);
  EXPECT_GT(g.focalPx, 0);
  EXPECT_GT(g.baseline, 0);
  // The baseline equals |T| (rectification only rotates).
  EXPECT_NEAR(g.baseline, cv::norm(calibration_->T), 1e-9 * g.baseline);
  EXPECT_GE(g.cx, 0);
  EXPECT_LE(g.cx, calibration_->imageSize.width);
}

TEST_F(OpenCVViews, RectifierAlignsTheBoardRows) {
  StereoRectifier stage(*calibration_);
  const cv::Mat l = cv::imread(dir_ + "/left01.jpg", cv::IMREAD_GRAYSCALE);
  const cv::Mat r = cv::imread(dir_ + "/right01.jpg", cv::IMREAD_GRAYSCALE);
  stage.rectify(l, r);
  const std::vector<cv::Point2f> cl = findBoardCorners(stage.left(), kBoard);
  const std::vector<cv::Point2f> cr = findBoardCorners(stage.right(), kBoard);
  ASSERT_EQ(cl.size(), 54u);
  ASSERT_EQ(cr.size(), 54u);
  double sum = 0;
  for (std::size_t i = 0; i < cl.size(); ++i)
    sum += std::abs(cl[i].y - cr[i].y);
  EXPECT_LT(sum / cl.size(), 1.0);
  // Buffers are reused from frame to frame.
  const uchar* before = stage.left().data;
  stage.rectify(l, r);
  EXPECT_EQ(stage.left().data, before);
  expectError([&] { stage.rectify(cv::Mat(10, 10, CV_8UC1), r); }, {"left", "10x10"});
}

TEST_F(OpenCVViews, TooFewViewsIsAClearError) {
  BoardDetections few = *detections_;
  few.views.resize(2);
  expectError(
      [&] {
        calibrateStereo(few, {kBoard, kSquare});
      },
      {"only 2 of", "at least 5", "blank pair"});
  expectError([&] { calibrateStereo(*detections_, {kBoard, 0.0}); }, {"square size"});
}

TEST_F(OpenCVViews, FileRoundTripsThroughFileStorage) {
  const std::string path = ::testing::TempDir() + "horopter_calib_roundtrip.yml";
  saveStereoCalibration(*calibration_, path);
  const StereoCalibration back = loadStereoCalibration(path);
  const StereoCalibration& c = *calibration_;
  const std::vector<std::pair<const char*, std::pair<cv::Mat, cv::Mat>>> mats = {
      {"K1", {c.K1, back.K1}}, {"D1", {c.D1, back.D1}}, {"K2", {c.K2, back.K2}},
      {"D2", {c.D2, back.D2}}, {"R", {c.R, back.R}},    {"T", {c.T, back.T}},
      {"E", {c.E, back.E}},    {"F", {c.F, back.F}},    {"R1", {c.R1, back.R1}},
      {"R2", {c.R2, back.R2}}, {"P1", {c.P1, back.P1}}, {"P2", {c.P2, back.P2}},
      {"Q", {c.Q, back.Q}}};
  for (const auto& [name, m] : mats) {
    ASSERT_EQ(m.first.size(), m.second.size()) << name;
    EXPECT_LE(cv::norm(m.first, m.second, cv::NORM_INF), 1e-12 * (1 + cv::norm(m.first))) << name;
  }
  EXPECT_EQ(back.imageSize, c.imageSize);
  EXPECT_EQ(back.roi1, c.roi1);
  EXPECT_EQ(back.roi2, c.roi2);
  EXPECT_EQ(back.board.innerCorners, kBoard);
  EXPECT_DOUBLE_EQ(back.board.squareSize, kSquare);
  EXPECT_DOUBLE_EQ(back.rms, c.rms);
  EXPECT_DOUBLE_EQ(back.epipolarError, c.epipolarError);
  ASSERT_EQ(back.views.size(), c.views.size());
  EXPECT_EQ(back.views[0].name, c.views[0].name);
  EXPECT_EQ(back.boardHomographies.size(), c.boardHomographies.size());
  EXPECT_EQ(back.skipped, c.skipped);

  // Any cv::FileStorage user reads it.
  cv::FileStorage fs(path, cv::FileStorage::READ);
  cv::Mat p2;
  fs["P2"] >> p2;
  EXPECT_EQ(cv::norm(p2, c.P2, cv::NORM_INF), 0.0);
  std::remove(path.c_str());
}

// Mean |y_left - y_right| of the detected corners after rectification
// with `c` (independent of calibrateStereo's own figure).
double epipolarErrorWith(const BoardDetections& d, const StereoCalibration& c) {
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

// The real calibration through the formats of other tools: an OpenCV file
// as a cv2 user saves stereoCalibrate's output (K1..T and the image size,
// no rectification), and a ROS camera_info pair. Both must rectify as the
// original does.
TEST_F(OpenCVViews, OpenCvAndRosFilesOfTheRealCalibrationRectifyAlike) {
  const StereoCalibration& c = *calibration_;
  const std::filesystem::path dir =
      std::filesystem::path(::testing::TempDir()) / "horopter_real_formats";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  {
    cv::FileStorage fs((dir / "stereo.yml").string(), cv::FileStorage::WRITE);
    fs << "image_width" << c.imageSize.width << "image_height" << c.imageSize.height;
    fs << "K1" << c.K1 << "D1" << c.D1 << "K2" << c.K2 << "D2" << c.D2 << "R" << c.R << "T" << c.T;
  }
  const StereoCalibration opencv = loadStereoCalibration((dir / "stereo.yml").string());
  // The same cv::stereoRectify on the same numbers.
  for (const auto& [name, a, b] :
       {std::tuple{"P1", c.P1, opencv.P1}, std::tuple{"P2", c.P2, opencv.P2},
        std::tuple{"R1", c.R1, opencv.R1}, std::tuple{"Q", c.Q, opencv.Q}})
    EXPECT_LE(cv::norm(a, b, cv::NORM_INF), 1e-9 * (1 + cv::norm(a))) << name;
  EXPECT_EQ(opencv.roi1, c.roi1);
  EXPECT_NEAR(epipolarErrorWith(*detections_, opencv), c.epipolarError, 1e-6);

  writeRosCameraInfo(c, (dir / "left.yaml").string(), (dir / "right.yaml").string());
  const StereoCalibration ros = loadStereoCalibration(dir.string());
  // R and T recovered from the rectification: R = R2^T R1, T = R2^T t.
  EXPECT_LE(cv::norm(ros.R, c.R, cv::NORM_INF), 1e-12);
  EXPECT_LE(cv::norm(ros.T, c.T, cv::NORM_INF), 1e-12 * cv::norm(c.T));
  EXPECT_LE(cv::norm(ros.Q, c.Q, cv::NORM_INF), 1e-9 * cv::norm(c.Q));
  EXPECT_EQ(epipolarErrorWith(*detections_, ros), c.epipolarError);

  // The imported calibration's rectifier aligns the board's rows.
  StereoRectifier stage(ros);
  stage.rectify(cv::imread(dir_ + "/left01.jpg", cv::IMREAD_GRAYSCALE),
                cv::imread(dir_ + "/right01.jpg", cv::IMREAD_GRAYSCALE));
  const std::vector<cv::Point2f> cl = findBoardCorners(stage.left(), kBoard);
  const std::vector<cv::Point2f> cr = findBoardCorners(stage.right(), kBoard);
  ASSERT_EQ(cl.size(), 54u);
  ASSERT_EQ(cr.size(), 54u);
  double sum = 0;
  for (std::size_t i = 0; i < cl.size(); ++i)
    sum += std::abs(cl[i].y - cr[i].y);
  EXPECT_LT(sum / cl.size(), 1.0);
  std::filesystem::remove_all(dir);
}

TEST_F(OpenCVViews, MalformedFilesNameTheField) {
  const std::string full = ::testing::TempDir() + "horopter_calib_full.yml";
  saveStereoCalibration(*calibration_, full);
  std::ifstream in(full);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // Drop the P2 matrix (its key line and the lines of its body).
  const std::size_t start = text.find("P2:");
  ASSERT_NE(start, std::string::npos);
  const std::size_t end = text.find("\nQ:", start);
  ASSERT_NE(end, std::string::npos);
  const std::string broken = ::testing::TempDir() + "horopter_calib_no_p2.yml";
  std::ofstream(broken) << text.substr(0, start) << text.substr(end + 1);
  expectError([&] { loadStereoCalibration(broken); }, {"'P2'", "missing", "3x4"});

  // A matrix header with a huge or a non-integer size is an error before
  // OpenCV allocates anything (the fuzz target found "rows: *" asking for
  // gigabytes).
  const std::size_t k1 = text.find("rows: 3", text.find("K1:"));
  ASSERT_NE(k1, std::string::npos);
  const std::string huge = ::testing::TempDir() + "horopter_calib_huge.yml";
  std::ofstream(huge) << text.substr(0, k1) << "rows: 2000000000" << text.substr(k1 + 7);
  expectError([&] { loadStereoCalibration(huge); }, {"'K1'", "2000000000x3", "3x3"});
  std::ofstream(huge) << text.substr(0, k1) << "rows: *" << text.substr(k1 + 7);
  expectError([&] { loadStereoCalibration(huge); }, {"'K1'", "not an OpenCV matrix"});
  // A view's homography whose data does not fill it: OpenCV asserts inside
  // the read; the error names the field (also found by the fuzz target).
  const std::size_t h = text.find("rows: 3", text.find("board_homography"));
  ASSERT_NE(h, std::string::npos);
  std::ofstream(huge) << text.substr(0, h) << "rows: 4" << text.substr(h + 7);
  expectError([&] { loadStereoCalibration(huge); }, {"'views'", "3x3"});
  // Text on which OpenCV's YAML parser throws std::length_error, not
  // cv::Exception (the fuzz target's mutation of K1's data line).
  const std::size_t d = text.find("data: [", text.find("K1:"));
  ASSERT_NE(d, std::string::npos);
  std::ofstream(huge) << text.substr(0, d) << ":a[tad " << text.substr(d + 7);
  expectError([&] { loadStereoCalibration(huge); }, {"horopter_calib_huge.yml"});
  std::ofstream(huge) << "%YAML:1.0\n---\n- 1\n- 2\n";
  expectError([&] { loadStereoCalibration(huge); }, {"named fields at the top level"});
  std::remove(huge.c_str());

  const std::string garbage = ::testing::TempDir() + "horopter_calib_garbage.yml";
  std::ofstream(garbage) << "%YAML:1.0\n---\nimage_width: [1, 2\n";
  expectError([&] { loadStereoCalibration(garbage); }, {"horopter_calib_garbage.yml"});
  expectError([&] { loadStereoCalibration(::testing::TempDir() + "no-such-calib.yml"); },
              {"does not exist"});
  for (const std::string& p : {full, broken, garbage})
    std::remove(p.c_str());
}

// (c) from calibrated extrinsics, on a synthetic toed-in rig: each camera
// turned inward by `a`, so the optical axes meet on the head's axis at
// z = (B/2) / tan(a). The extrinsics go through cv::stereoRectify like a real
// calibration.
TEST(CalibrationGeometry, OpticalAxesOfAToedInRigMeetAtTheExpectedFixation) {
  const double b = 0.12;
  for (double deg : {1.0, 3.0, 8.0}) {
    const double a = deg * std::numbers::pi / 180.0;
    const cv::Matx33d ry(std::cos(a), 0, std::sin(a), 0, 1, 0, -std::sin(a), 0, std::cos(a));
    StereoCalibration c;
    c.imageSize = {640, 480};
    c.K1 = (cv::Mat_<double>(3, 3) << 500, 0, 320, 0, 500, 240, 0, 0, 1);
    c.K2 = c.K1.clone();
    c.D1 = cv::Mat::zeros(1, 5, CV_64F);
    c.D2 = c.D1.clone();
    // Left camera-to-world Ry(a), right Ry(-a): X2 = Ry(a) Ry(a) X1 + Ry(a) (-B, 0, 0).
    c.R = cv::Mat(ry * ry);
    c.T = cv::Mat(ry * cv::Vec3d(-b, 0, 0));
    cv::stereoRectify(c.K1, c.D1, c.K2, c.D2, c.imageSize, c.R, c.T, c.R1, c.R2, c.P1, c.P2, c.Q,
                      cv::CALIB_ZERO_DISPARITY, 0.0);
    const auto [left, right] = opticalAxes(c);
    const Eigen::Vector3d f = fixationFromAxes(left, right);
    const double z = 0.5 * b / std::tan(a);
    EXPECT_NEAR(f.x(), 0.0, 1e-9 * z) << deg << " deg";
    EXPECT_NEAR(f.y(), 0.0, 1e-9 * z) << deg << " deg";
    EXPECT_NEAR(f.z(), z, 1e-9 * z) << deg << " deg";
    EXPECT_NEAR(vergenceAngleAt(b, f), 2 * a, 1e-9);
  }
}

TEST(CalibrationInput, BoardSizeText) {
  EXPECT_EQ(parseBoardSize("9x6"), cv::Size(9, 6));
  expectError([] { parseBoardSize("9*6"); }, {"COLSxROWS", "9*6"});
  expectError([] { parseBoardSize("1x6"); }, {"2x2"});
  expectError([] { parseBoardSize("7x7"); }, {"square board"});
}

TEST(CalibrationInput, PairsOfAnotherSizeAreSkippedAndNamed) {
  const auto grey = [](int w, int h) { return cv::Mat(h, w, CV_8UC1, cv::Scalar(0)); };
  const std::vector<StereoImagePair> pairs{{"odd pair", grey(64, 48), grey(64, 40)},
                                           {"a", grey(64, 48), grey(64, 48)},
                                           {"b", grey(64, 48), grey(64, 48)},
                                           {"stray", grey(32, 24), grey(32, 24)},
                                           {"empty", cv::Mat(), grey(64, 48)}};
  const BoardDetections none = detectBoards(pairs, kBoard);
  EXPECT_EQ(none.imageSize, cv::Size(64, 48));
  EXPECT_TRUE(none.views.empty());
  ASSERT_EQ(none.skipped.size(), 5u);
  EXPECT_EQ(none.skipped[0], "odd pair: left is 64x48 but right is 64x40");
  EXPECT_EQ(none.skipped[1], "a: no 9x6 board in either image");
  EXPECT_EQ(none.skipped[3], "stray: it is 32x24, not the 64x48 of most views");
  EXPECT_EQ(none.skipped[4], "empty: an image is empty");
  expectError(
      [&] {
        calibrateStereo(none, {kBoard, kSquare}, {3, 0.0});
      },
      {"only 0 of 5", "at least 3", "stray"});
}

}  // namespace
}  // namespace horopter::test
