// Evaluation: scores on hand-built maps, ground-truth loading, and the
// Horopter / cv::StereoBM runners.
#include <unistd.h>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "horopter/core/error.hpp"
#include "horopter/eval/stereo_eval.hpp"
#include "horopter/vision/frontend.hpp"
#include "horopter/vision/opencv.hpp"
#include "io/disparity_images.hpp"
#include "test_support.hpp"

namespace horopter::test {
namespace {

// A scratch folder, removed at the end of the test.
class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() /
            ("horopter-test-" + std::to_string(::getpid()) + "-" + info->name());
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

template <typename F>
::testing::AssertionResult throwsMentioning(F&& f, const std::string& word) {
  try {
    f();
  } catch (const Error& e) {
    if (std::string(e.what()).find(word) != std::string::npos) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "\"" << e.what() << "\" does not mention " << word;
  }
  return ::testing::AssertionFailure() << "no horopter::Error; expected one mentioning " << word;
}

// One row: errors 0, 0.5, 1.5, 2.5 px, one invalid output, errors of exactly
// 1 and exactly 2 px (not "more than"), two pixels without ground truth (0
// and negative).
TEST(Eval, ScoresHandBuiltMap) {
  const std::int16_t inv = -16;
  const float gt[9] = {1.0f, 2.0f, 3.0f, 4.0f, 5.0f, 0.0f, 6.0f, -1.0f, 7.0f};
  const std::int16_t d[9] = {16, 2 * 16 + 8,  3 * 16 + 24, 4 * 16 - 40, inv,
                             99, 6 * 16 + 16, inv,         7 * 16 - 32};
  cv::Mat gtMat(1, 9, CV_32F);
  for (int i = 0; i < 9; ++i)
    gtMat.at<float>(0, i) = gt[i];
  const ConstImageView view{d, 9, 1, sizeof d, PixelType::S16C1};
  const StereoScores s = scoreDisparity(view, inv, gtMat);
  // Known: 7 pixels. Valid: 6, errors 0, 0.5, 1.5, 2.5, 1.0, 2.0.
  EXPECT_DOUBLE_EQ(s.bad1, 100.0 * 4 / 7);  // 1.5, 2.5, 2.0, invalid
  EXPECT_DOUBLE_EQ(s.bad2, 100.0 * 2 / 7);  // 2.5, invalid
  EXPECT_DOUBLE_EQ(s.avgerr, (0 + 0.5 + 1.5 + 2.5 + 1.0 + 2.0) / 6);
  EXPECT_DOUBLE_EQ(s.density, 100.0 * 6 / 7);
}

TEST(Eval, PerfectAndEmptyMaps) {
  const int w = 40, h = 30;
  cv::Mat gt(h, w, CV_32F);
  TestImage d(w, h, PixelType::S16C1);
  Rng rng(4);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int v16 = rng.uniform(16, 64 * 16);
      gt.at<float>(y, x) = v16 / 16.0f;
      d.at<std::int16_t>(x, y) = static_cast<std::int16_t>(v16);
    }
  const StereoScores perfect = scoreDisparity(d.view(), -16, gt);
  EXPECT_EQ(perfect.bad1, 0);
  EXPECT_EQ(perfect.bad2, 0);
  EXPECT_EQ(perfect.avgerr, 0);
  EXPECT_EQ(perfect.density, 100);
  d.fillBytes(0xF0);  // every pixel -3856
  const StereoScores none = scoreDisparity(d.view(), static_cast<std::int16_t>(0xF0F0), gt);
  EXPECT_EQ(none.bad1, 100);
  EXPECT_EQ(none.bad2, 100);
  EXPECT_EQ(none.density, 0);
  EXPECT_EQ(none.avgerr, 0);
}

TEST(Eval, ScoresAStridedViewLikeATightCopy) {
  const int w = 37, h = 11;
  cv::Mat gt(h, w, CV_32F);
  Rng rng(8);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      gt.at<float>(y, x) = rng.chance(20) ? 0.0f : rng.uniform(1, 40) / 4.0f;
  StereoParams p;
  p.numDisparities = 48;
  const TestImage tight = randomDisparityMap(w, h, p, 3, 25);
  const TestImage roi = tight.clone(kRoi);
  const StereoScores a = scoreDisparity(tight.view(), invalidDisparity(p), gt);
  const StereoScores b = scoreDisparity(roi.view(), invalidDisparity(p), gt);
  EXPECT_EQ(a.bad1, b.bad1);
  EXPECT_EQ(a.bad2, b.bad2);
  EXPECT_EQ(a.avgerr, b.avgerr);
  EXPECT_EQ(a.density, b.density);
  EXPECT_GT(a.bad1, 0);
  EXPECT_LT(a.density, 100);
}

TEST(Eval, ScoringRejectsBadGroundTruth) {
  TestImage d(10, 5, PixelType::S16C1);
  EXPECT_TRUE(throwsMentioning([&] { scoreDisparity(d.view(), -16, cv::Mat::ones(5, 10, CV_8U)); },
                               "CV_32FC1"));
  EXPECT_TRUE(throwsMentioning([&] { scoreDisparity(d.view(), -16, cv::Mat::ones(5, 11, CV_32F)); },
                               "size"));
  EXPECT_TRUE(throwsMentioning(
      [&] { scoreDisparity(d.view(), -16, cv::Mat::zeros(5, 10, CV_32F)); }, "no known pixel"));
  TestImage u8(10, 5, PixelType::U8C1);
  EXPECT_TRUE(throwsMentioning(
      [&] { scoreDisparity(u8.view(), -16, cv::Mat::ones(5, 10, CV_32F)); }, "disparity"));
}

TEST(Eval, LoadGroundTruthDividesByScale) {
  TempDir dir;
  cv::Mat raw8(6, 9, CV_8U), raw16(6, 9, CV_16U);
  Rng rng(2);
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 9; ++x) {
      raw8.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(rng.uniform(0, 255));
      raw16.at<std::uint16_t>(y, x) = static_cast<std::uint16_t>(rng.uniform(0, 65535));
    }
  ASSERT_TRUE(cv::imwrite(dir.file("gt8.png"), raw8));
  ASSERT_TRUE(cv::imwrite(dir.file("gt16.png"), raw16));
  ASSERT_TRUE(cv::imwrite(dir.file("gt8.pgm"), raw8));
  for (const char* name : {"gt8.png", "gt8.pgm", "gt16.png"}) {
    const bool wide = std::string(name) == "gt16.png";
    for (double scale : {1.0, 4.0, 16.0, 256.0}) {
      const cv::Mat px = loadGroundTruth(dir.file(name), scale);
      ASSERT_EQ(px.type(), CV_32FC1);
      ASSERT_EQ(px.size(), raw8.size());
      for (int y = 0; y < 6; ++y)
        for (int x = 0; x < 9; ++x) {
          const double v = wide ? raw16.at<std::uint16_t>(y, x) : raw8.at<std::uint8_t>(y, x);
          ASSERT_FLOAT_EQ(px.at<float>(y, x), static_cast<float>(v / scale)) << name;
        }
    }
  }
}

// Middlebury's PFM ground truth: float px divided by the scale, inf = unknown.
TEST(Eval, LoadGroundTruthReadsPfm) {
  TempDir dir;
  cv::Mat px(3, 4, CV_32FC1);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x)
      px.at<float>(y, x) = 10.25f * y + x + 0.5f;
  px.at<float>(1, 2) = std::numeric_limits<float>::infinity();
  const std::string path = dir.file("gt.pfm");
  writePfm(path, px);
  for (double scale : {1.0, 2.0}) {
    const cv::Mat gt = loadGroundTruth(path, scale);
    ASSERT_EQ(gt.type(), CV_32FC1);
    ASSERT_EQ(gt.size(), px.size());
    for (int y = 0; y < 3; ++y)
      for (int x = 0; x < 4; ++x)
        EXPECT_FLOAT_EQ(gt.at<float>(y, x),
                        y == 1 && x == 2 ? 0.0f : static_cast<float>(px.at<float>(y, x) / scale));
  }
}

TEST(Eval, LoadingErrorsNameTheFileOrScale) {
  TempDir dir;
  const std::string missing = dir.file("no-such-gt.png");
  EXPECT_TRUE(throwsMentioning([&] { loadGroundTruth(missing, 16); }, missing));
  EXPECT_TRUE(throwsMentioning([&] { loadGroundTruth(missing, 0); }, "scale"));
  EXPECT_TRUE(throwsMentioning([&] { loadGroundTruth(missing, -4); }, "scale"));
  EXPECT_TRUE(throwsMentioning([&] { loadGrey(missing, "left image"); }, missing));
  EXPECT_TRUE(throwsMentioning([&] { loadGrey(missing, "left image"); }, "left image"));
  // A file that is not an image.
  const std::string text = dir.file("not-an-image.png");
  std::ofstream(text) << "this is not a PNG file\n";
  EXPECT_TRUE(throwsMentioning([&] { loadGroundTruth(text, 1); }, "could not be decoded"));
  EXPECT_TRUE(throwsMentioning([&] { loadGrey(text, "right image"); }, "could not be decoded"));
  // A folder is not a file.
  EXPECT_TRUE(throwsMentioning([&] { loadGrey(dir.file(""), "left image"); }, "not a file"));
  // A colour image is read as grey.
  cv::Mat colour(4, 5, CV_8UC3, cv::Scalar(10, 20, 30));
  ASSERT_TRUE(cv::imwrite(dir.file("colour.png"), colour));
  const cv::Mat grey = loadGrey(dir.file("colour.png"), "left image");
  EXPECT_EQ(grey.type(), CV_8UC1);
  EXPECT_EQ(grey.size(), colour.size());
}

// The evaluation of Horopter equals the front end run and scored by hand.
TEST(Eval, EvaluateHoropterEqualsFrontendThenScore) {
  const int w = 160, h = 60;
  StereoParams p;
  p.numDisparities = 32;
  const StereoPair pair = stepScenePair(w, h, StepScene{70, 130, 15, 45, 25, 6}, 11);
  cv::Mat gt(h, w, CV_32F, cv::Scalar(6.0f));
  gt(cv::Rect(70, 15, 60, 30)).setTo(25.0f);
  const cv::Mat left = matOf(pair.left.view()).clone(), right = matOf(pair.right.view()).clone();
  EvalOptions options;
  options.warmupRuns = 0;
  options.timedRuns = 2;
  const StereoScores s =
      evaluateHoropter(left, right, gt, p, MedianParams{}, scalarBackend(), options);
  StereoFrontend frontend(p, MedianParams{});
  frontend.computeDisparity(viewOf(left), viewOf(right));
  const StereoScores want = scoreDisparity(frontend.disparity().view(), invalidDisparity(p), gt);
  EXPECT_EQ(s.bad1, want.bad1);
  EXPECT_EQ(s.bad2, want.bad2);
  EXPECT_EQ(s.avgerr, want.avgerr);
  EXPECT_EQ(s.density, want.density);
  EXPECT_EQ(s.backend, "scalar");
  EXPECT_GE(s.ms, 0);
  // The scene is easy: most known pixels are right.
  EXPECT_LT(s.bad2, 50);

  const StereoScores bm = evaluateOpenCvStereoBM(left, right, gt, p, options);
  EXPECT_EQ(bm.backend, "opencv-stereobm");
  EXPECT_GT(bm.density, 0);
  EXPECT_LT(bm.bad2, 50);
}

TEST(Eval, EvaluationRejectsMismatchedInputs) {
  const cv::Mat a(30, 60, CV_8U, cv::Scalar(1)), b(30, 61, CV_8U, cv::Scalar(1));
  const cv::Mat gt(30, 60, CV_32F, cv::Scalar(1.0f)), gtSmall(29, 60, CV_32F, cv::Scalar(1.0f));
  StereoParams p;
  p.numDisparities = 16;
  EXPECT_TRUE(throwsMentioning(
      [&] { evaluateHoropter(a, b, gt, p, MedianParams{}, scalarBackend()); }, "differ in size"));
  EXPECT_TRUE(
      throwsMentioning([&] { evaluateHoropter(a, a, gtSmall, p, MedianParams{}, scalarBackend()); },
                       "ground truth is 60x29"));
  EXPECT_TRUE(throwsMentioning([&] { evaluateOpenCvStereoBM(a, b, gt, p); }, "differ in size"));
  p.blockSize = 3;
  EXPECT_TRUE(throwsMentioning([&] { evaluateOpenCvStereoBM(a, a, gt, p); }, "blockSize"));
  p.blockSize = 8;
  EXPECT_TRUE(throwsMentioning([&] { evaluateOpenCvStereoBM(a, a, gt, p); }, "blockSize"));
}

}  // namespace
}  // namespace horopter::test
