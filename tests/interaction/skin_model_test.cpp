// The skin model: the threshold box on known colours, training from labelled
// pixels, bad input.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "horopter/core/error.hpp"
#include "horopter/interaction/skin_model.hpp"

namespace horopter {
namespace {

TEST(SkinModel, ThresholdsAcceptSkinTonesAndRejectOthers) {
  const SkinModel model;
  // The synthetic scene's skin (BGR gain 0.82, 1.09, 1.52 on grey 150) and a
  // darker and a paler skin tone.
  for (cv::Vec3b skin :
       {cv::Vec3b(123, 163, 228), cv::Vec3b(80, 110, 160), cv::Vec3b(150, 180, 230)})
    EXPECT_TRUE(model.isSkinBgr(skin)) << skin;
  for (cv::Vec3b other : {cv::Vec3b(200, 60, 40), cv::Vec3b(60, 160, 60), cv::Vec3b(128, 128, 128),
                          cv::Vec3b(0, 0, 0), cv::Vec3b(255, 255, 255), cv::Vec3b(20, 20, 200)})
    EXPECT_FALSE(model.isSkinBgr(other)) << other;
}

TEST(SkinModel, ClassifyMarksTheSkinPatchOnly) {
  cv::Mat image(40, 60, CV_8UC3, cv::Scalar(180, 90, 60));  // blue background
  image(cv::Rect(20, 10, 15, 12)).setTo(cv::Scalar(123, 163, 228));
  cv::Mat out;
  SkinModel().classify(image, cv::Rect(5, 5, 50, 30), out);
  ASSERT_EQ(out.size(), cv::Size(50, 30));
  EXPECT_EQ(cv::countNonZero(out), 15 * 12);
  EXPECT_EQ(out.at<std::uint8_t>(10 - 5 + 3, 20 - 5 + 3), 255);
}

TEST(SkinModel, TrainedFromLabelledPixelsSeparatesTheTwoClasses) {
  // Skin: a spread of warm tones; not skin: greens, blues and a wood-like
  // orange that the threshold box would call skin.
  cv::RNG rng(7);
  cv::Mat image(64, 64, CV_8UC3), labels(64, 64, CV_8UC1);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const bool skin = x < 32;
      const int j = rng.uniform(-8, 9);
      image.at<cv::Vec3b>(y, x) =
          skin ? cv::Vec3b(static_cast<uchar>(120 + j), static_cast<uchar>(160 + j),
                           static_cast<uchar>(225 + j / 2))
               : (y < 32 ? cv::Vec3b(static_cast<uchar>(60 + j), 150, 60)
                         : cv::Vec3b(60, static_cast<uchar>(130 + j), 210));
      labels.at<std::uint8_t>(y, x) = skin ? 255 : 0;
    }
  const SkinModel model = SkinModel::train({image}, {labels});
  EXPECT_TRUE(model.isSkinBgr({123, 163, 228}));
  EXPECT_FALSE(model.isSkinBgr({60, 150, 60}));
  EXPECT_FALSE(model.isSkinBgr({60, 130, 210})) << "the labelled orange is not skin";
  EXPECT_TRUE(SkinModel().isSkinBgr({60, 130, 210})) << "while the threshold box takes it";
}

TEST(SkinModel, BadInputIsAnError) {
  cv::Mat image(4, 4, CV_8UC3, cv::Scalar::all(0)), labels(4, 4, CV_8UC1, cv::Scalar(255));
  EXPECT_THROW(SkinModel::train({image}, {}), Error);
  EXPECT_THROW(SkinModel::train({image}, {labels}), Error) << "no non-skin pixels";
  EXPECT_THROW(SkinModel::train({image}, {cv::Mat(3, 4, CV_8UC1)}), Error);
  SkinThresholds bad;
  bad.crMin = 200;
  bad.crMax = 100;
  EXPECT_THROW(SkinModel{bad}, Error);
  cv::Mat out;
  EXPECT_THROW(SkinModel().classify(cv::Mat(4, 4, CV_8UC1), cv::Rect(0, 0, 4, 4), out), Error);
}

}  // namespace
}  // namespace horopter
