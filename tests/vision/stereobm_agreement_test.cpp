// Horopter against cv::StereoBM itself, pixel by pixel, on the real Middlebury
// pairs in ../shared/data: both set up with StereoBM's own defaults
// (stereoBMDefaults(n, b) here, cv::StereoBM::create(n, b) there, then the
// same settings on both sides), no median. Counted per pair: pixels valid in
// both that differ, pixels valid in only one of them.
//
// Measured with the scalar reference (every backend gives its output bit for
// bit), OpenCV 4.6 (Debian's): valid in both / differing by +1/16 px /
// differing otherwise / valid in one only
//   tsukuba, x-Sobel:     87148 / 37926 / 1 / 2
//   tsukuba, normalized:  85548 / 37106 / 0 / 9
//   teddy, x-Sobel:      114993 / 50684 / 5 / 10
//   teddy, normalized:   118741 / 52426 / 0 / 10
// Why they differ (kernels/README.md, "Agreement with cv::StereoBM"):
//   - Sub-pixel rounding: both fit the same line through the same integer
//     costs, but StereoBM rounds the 1/16 px value up, (v * 16 + 15) >> 4 in
//     its terms, where Horopter's reference rounds to nearest ((v + 8) >> 4):
//     StereoBM's value is Horopter's + 1 on about 44 % of the valid pixels,
//     never anything else for that reason. Changing Horopter's rounding would
//     change every front end's output (and the SAD kernels), so it is stated
//     here rather than copied.
//   - Ties: StereoBM scans its costs from the largest disparity down and
//     keeps the first least cost (the largest d); Horopter keeps the smallest
//     d. Where two adjacent disparities tie, the winner differs by one pixel,
//     and with it the uniqueness test's excluded neighbours: a few pixels
//     (at most 10 here) are valid on one side only, or differ by more.
//   - x-Sobel, odd heights: StereoBM's prefilterXSobel filters rows in pairs
//     and fills the last row of an odd-height image with the cap (a zero
//     response); Horopter's reference filters it as every other row. Teddy
//     (375 rows) has it: its bottom windows (row 364 with block 21) differ.
//   - The normalized-response prefilter is StereoBM's integer arithmetic bit
//     for bit: with it, nothing but the rounding and the ties differs.
#include <cstdint>
#include <iostream>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>

#include "horopter/eval/stereo_eval.hpp"
#include "horopter/vision/frontend.hpp"
#include "horopter/vision/opencv.hpp"
#include "test_support.hpp"

namespace horopter::test {
namespace {

struct Agreement {
  long bothValid = 0;
  long bothValidDiffer = 0;    // by anything
  long roundedUpByOpenCv = 0;  // OpenCV's value is Horopter's + 1 (1/16 px)
  long otherwise = 0;          // both valid, differing by anything else
  long onlyOurs = 0;
  long onlyOpenCv = 0;
};

Agreement compareWithStereoBM(const cv::Mat& left, const cv::Mat& right, const StereoParams& p) {
  StereoFrontend ours(p, MedianParams{0, 0}, scalarBackend(), 1);
  ours.computeDisparity(viewOf(left), viewOf(right));
  cv::Mat theirs;
  makeOpenCvStereoBM(p)->compute(left, right, theirs);
  const std::int16_t invalid = invalidDisparity(p);
  Agreement a;
  const ConstImageView d = ours.disparity().view();
  for (int y = 0; y < left.rows; ++y) {
    const auto* o = d.row<std::int16_t>(y);
    const auto* t = theirs.ptr<std::int16_t>(y);
    for (int x = 0; x < left.cols; ++x) {
      // OpenCV marks invalid pixels with its FILTERED value, (minDisparity - 1) * 16.
      const bool ov = o[x] != invalid, tv = t[x] != invalid;
      if (ov && tv) {
        ++a.bothValid;
        if (o[x] != t[x]) ++a.bothValidDiffer;
        if (t[x] == o[x] + 1)
          ++a.roundedUpByOpenCv;
        else if (o[x] != t[x])
          ++a.otherwise;
      } else if (ov) {
        ++a.onlyOurs;
      } else if (tv) {
        ++a.onlyOpenCv;
      }
    }
  }
  return a;
}

struct PairCase {
  const char* name;
  std::string left, right;
  int numDisparities;
  PreFilterType type;
  // Measured bounds (see the file comment).
  long maxOtherwise, maxOnlyOne;
};

void checkPair(const PairCase& c) {
  HOROPTER_REQUIRE_FILE(c.left);
  HOROPTER_REQUIRE_FILE(c.right);
  const cv::Mat left = cv::imread(c.left, cv::IMREAD_GRAYSCALE);
  const cv::Mat right = cv::imread(c.right, cv::IMREAD_GRAYSCALE);
  ASSERT_FALSE(left.empty()) << c.left;
  StereoParams p = stereoBMDefaults(c.numDisparities);
  p.preFilterType = c.type;
  const Agreement a = compareWithStereoBM(left, right, p);
  std::cout << c.name << " (" << toString(c.type) << "): " << a.bothValid << " valid in both, "
            << a.bothValidDiffer << " of them differ (" << a.roundedUpByOpenCv << " by +1/16 px, "
            << a.otherwise << " otherwise); only Horopter " << a.onlyOurs << ", only StereoBM "
            << a.onlyOpenCv << "\n";
  EXPECT_GT(a.bothValid, left.total() / 4) << c.name;
  // Every pixel that differs does so by the rounding, apart from the few
  // explained above.
  EXPECT_EQ(a.bothValidDiffer, a.roundedUpByOpenCv + a.otherwise) << c.name;
  EXPECT_LE(a.otherwise, c.maxOtherwise) << c.name;
  EXPECT_LT(a.roundedUpByOpenCv, a.bothValid * 6 / 10) << c.name;
  EXPECT_LE(a.onlyOurs + a.onlyOpenCv, c.maxOnlyOne) << c.name;
}

std::string middlebury(const std::string& f) {
  return sharedDataDir() + "/middlebury/" + f;
}

TEST(StereoBMAgreement, TsukubaXSobelDefaults) {
  checkPair({"tsukuba", middlebury("tsukuba/im3.png"), middlebury("tsukuba/im4.png"), 16,
             PreFilterType::XSobel, 1, 2});
}

TEST(StereoBMAgreement, TsukubaNormalizedResponse) {
  checkPair({"tsukuba", middlebury("tsukuba/im3.png"), middlebury("tsukuba/im4.png"), 16,
             PreFilterType::NormalizedResponse, 0, 9});
}

TEST(StereoBMAgreement, TeddyXSobelDefaults) {
  checkPair({"teddy", middlebury("teddy/im2.png"), middlebury("teddy/im6.png"), 64,
             PreFilterType::XSobel, 5, 10});
}

TEST(StereoBMAgreement, TeddyNormalizedResponse) {
  checkPair({"teddy", middlebury("teddy/im2.png"), middlebury("teddy/im6.png"), 64,
             PreFilterType::NormalizedResponse, 0, 10});
}

// The defaults function is cv::StereoBM::create's, field by field.
TEST(StereoBMAgreement, DefaultsAreStereoBMs) {
  const cv::Ptr<cv::StereoBM> bm = cv::StereoBM::create();
  const StereoParams p = stereoBMDefaults();
  EXPECT_EQ(p.numDisparities, bm->getNumDisparities());
  EXPECT_EQ(p.blockSize, bm->getBlockSize());
  EXPECT_EQ(p.minDisparity, bm->getMinDisparity());
  EXPECT_EQ(static_cast<int>(p.preFilterType), bm->getPreFilterType());
  EXPECT_EQ(p.preFilterSize, bm->getPreFilterSize());
  EXPECT_EQ(p.preFilterCap, bm->getPreFilterCap());
  EXPECT_EQ(p.textureThreshold, bm->getTextureThreshold());
  EXPECT_EQ(p.uniquenessRatio, bm->getUniquenessRatio());
  EXPECT_EQ(p.speckleWindowSize, bm->getSpeckleWindowSize());
  EXPECT_EQ(p.speckleRange, bm->getSpeckleRange());
  EXPECT_EQ(p.disp12MaxDiff, bm->getDisp12MaxDiff());
  const cv::Ptr<cv::StereoBM> bm32 = cv::StereoBM::create(32, 15);
  EXPECT_EQ(stereoBMDefaults(32, 15).numDisparities, bm32->getNumDisparities());
  EXPECT_EQ(stereoBMDefaults(32, 15).blockSize, bm32->getBlockSize());
  EXPECT_EQ(static_cast<int>(PreFilterType::NormalizedResponse),
            cv::StereoBM::PREFILTER_NORMALIZED_RESPONSE);
  EXPECT_EQ(static_cast<int>(PreFilterType::XSobel), cv::StereoBM::PREFILTER_XSOBEL);
}

}  // namespace
}  // namespace horopter::test
