// cv::Mat interop: views share the Mat's memory and keep its stride.
#include <cstdint>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "horopter/core/error.hpp"
#include "horopter/kernels/kernels.hpp"
#include "horopter/vision/opencv.hpp"
#include "test_support.hpp"

namespace horopter::test {
namespace {

TEST(OpenCvInterop, ViewOfRoiKeepsStrideAndOrigin) {
  const std::pair<int, PixelType> types[] = {
      {CV_8UC1, PixelType::U8C1}, {CV_8UC3, PixelType::U8C3}, {CV_16SC1, PixelType::S16C1}};
  for (const auto& [cvType, type] : types) {
    cv::Mat full(80, 100, cvType);
    const cv::Mat roi = full(cv::Rect(10, 5, 40, 30));
    const ConstImageView v = viewOf(roi);
    EXPECT_EQ(v.data, roi.data);
    EXPECT_EQ(v.data, full.ptr(5) + 10 * full.elemSize());
    EXPECT_EQ(v.width, 40);
    EXPECT_EQ(v.height, 30);
    EXPECT_EQ(v.strideBytes, static_cast<std::ptrdiff_t>(full.step[0]));
    EXPECT_EQ(v.type, type);
    EXPECT_EQ(v.row<std::uint8_t>(3), roi.ptr(3));
  }
}

TEST(OpenCvInterop, MutableViewWritesThroughAndMatOfSharesMemory) {
  cv::Mat full(20, 30, CV_16SC1, cv::Scalar(0));
  cv::Mat roi = full(cv::Rect(3, 2, 10, 6));
  const ImageView v = mutableViewOf(roi);
  v.row<std::int16_t>(1)[4] = 1234;
  EXPECT_EQ(full.at<std::int16_t>(3, 7), 1234);

  const cv::Mat back = matOf(v);
  EXPECT_EQ(back.data, roi.data);
  EXPECT_EQ(back.step[0], full.step[0]);
  EXPECT_EQ(back.type(), CV_16SC1);
  EXPECT_EQ(back.size(), cv::Size(10, 6));
  EXPECT_EQ(back.at<std::int16_t>(1, 4), 1234);

  Image owned(17, 5, PixelType::U8C3);
  const cv::Mat ownedMat = matOf(owned);
  EXPECT_EQ(ownedMat.data, static_cast<const uchar*>(owned.view().data));
  EXPECT_EQ(static_cast<std::ptrdiff_t>(ownedMat.step[0]), owned.strideBytes());
  EXPECT_EQ(ownedMat.type(), CV_8UC3);
  EXPECT_TRUE(matOf(ConstImageView{}).empty());
}

TEST(OpenCvInterop, UnsupportedMatsThrow) {
  const auto mentions = [](const cv::Mat& m, const std::string& word) {
    try {
      viewOf(m);
    } catch (const Error& e) {
      return std::string(e.what()).find(word) != std::string::npos;
    }
    return false;
  };
  EXPECT_TRUE(mentions(cv::Mat(4, 4, CV_32FC1), "not supported"));
  EXPECT_TRUE(mentions(cv::Mat(4, 4, CV_16UC1), "CV_16UC1"));
  EXPECT_TRUE(mentions(cv::Mat(4, 4, CV_8UC4), "not supported"));
  EXPECT_TRUE(mentions(cv::Mat(), "empty"));
  const int dims[3] = {2, 3, 4};
  EXPECT_TRUE(mentions(cv::Mat(3, dims, CV_8UC1), "two-dimensional"));
  cv::Mat f(3, 3, CV_32FC1);
  EXPECT_THROW(mutableViewOf(f), Error);
}

// Kernels on a view into a Mat ROI give what they give on a packed copy.
TEST(OpenCvInterop, KernelsOnRoiViewsEqualPackedCopies) {
  const StereoPair pair = shiftedPair(140, 50, 9, Texture::Uniform, 12, 5);
  cv::Mat bigLeft(70, 180, CV_8UC1, cv::Scalar(3)), bigRight(70, 180, CV_8UC1, cv::Scalar(250));
  const cv::Rect where(23, 11, 140, 50);
  matOf(pair.left.view()).copyTo(bigLeft(where));
  matOf(pair.right.view()).copyTo(bigRight(where));
  const cv::Mat roiLeft = bigLeft(where), roiRight = bigRight(where);

  StereoParams p;
  p.numDisparities = 32;
  cv::Mat roiDisparity(50, 140, CV_16SC1), roiWinner(50, 140, CV_16SC1);
  cv::Mat bigTexture(70, 180, CV_8UC1, cv::Scalar(0));
  cv::Mat roiTexture = bigTexture(where);
  prefilterXSobel(viewOf(roiLeft), p.preFilterCap, {}, mutableViewOf(roiTexture));
  matchBlocks(viewOf(roiLeft), viewOf(roiRight), viewOf(roiTexture), p, mutableViewOf(roiDisparity),
              mutableViewOf(roiWinner));

  TestImage texture(140, 50, PixelType::U8C1), d(140, 50, PixelType::S16C1),
      wr(140, 50, PixelType::S16C1);
  prefilterXSobel(pair.left.view(), p.preFilterCap, {}, texture.view());
  matchBlocks(pair.left.view(), pair.right.view(), texture.view(), p, d.view(), wr.view());
  EXPECT_TRUE(sameImage(texture.view(), viewOf(roiTexture)));
  EXPECT_TRUE(sameImage(d.view(), viewOf(roiDisparity)));
  EXPECT_TRUE(sameImage(wr.view(), viewOf(roiWinner)));
  // Outside the ROI the texture buffer is untouched.
  EXPECT_EQ(cv::countNonZero(bigTexture) - cv::countNonZero(roiTexture), 0);
}

}  // namespace
}  // namespace horopter::test
