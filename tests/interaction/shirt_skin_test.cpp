// A shirt of skin's colour (engine/interaction/shirt_skin.hpp), on hand-made
// masks: the chest under the head is sampled, its median skin grey level
// read, and skin darker than a multiple of it called cloth only where the
// chest is mostly skin and darker than the face.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "horopter/interaction/detection.hpp"
#include "interaction/shirt_skin.hpp"

namespace horopter::detail {
namespace {

FaceDetection headAt(cv::Point2f centre, float width) {
  FaceDetection f;
  f.centre = centre;
  f.width = width;
  f.box = cv::Rect(cvRound(centre.x - width / 2), cvRound(centre.y - width / 2), cvRound(width),
                   cvRound(width));
  f.skinLuma = 140;
  return f;
}

const FaceDetection kHead = headAt({320, 100}, 60);

TEST(ShirtSkin, TheChestIsSampledUnderTheHead) {
  const DetectorOptions o;  // 1.5 to 2.7 head widths below, 0.5 either side
  const cv::Rect box = torsoBox(kHead, o);
  EXPECT_EQ(box, cv::Rect(cv::Point(290, 190), cv::Point(350, 262)));
  DetectorOptions wide = o;
  wide.shirtSampleHalfWidthFaces = 1;
  EXPECT_EQ(torsoBox(kHead, wide).width, 120);
}

TEST(ShirtSkin, TheSampleIsTheChestsSkinAndItsMedianLevel) {
  const DetectorOptions o;
  const cv::Rect roi(100, 50, 440, 400);  // the searched region, in the image
  cv::Mat skin(roi.size(), CV_8UC1, cv::Scalar(0)), grey(roi.size(), CV_8UC1, cv::Scalar(30));
  const cv::Rect chest = torsoBox(kHead, o) - roi.tl();
  skin(chest).setTo(255);
  grey(chest).setTo(70);
  // A bright hand before a quarter of the chest does not move its median.
  const cv::Rect hand(chest.x, chest.y, chest.width / 2, chest.height / 2);
  grey(hand).setTo(150);
  // A third of the chest not skin: the fraction falls, the level stays.
  const cv::Rect bare(chest.x + chest.width / 2, chest.y + chest.height / 2, chest.width / 2,
                      chest.height / 2);
  skin(bare).setTo(0);
  grey(bare).setTo(200);
  const TorsoSample s = sampleTorso(skin, grey, roi, kHead, o);
  EXPECT_EQ(s.pixels, chest.area());
  EXPECT_NEAR(s.skinFraction, 0.75, 0.01);
  EXPECT_EQ(s.skinLuma, 70);
  // Nothing of the box in the region: no sample.
  EXPECT_EQ(sampleTorso(skin, grey, roi, headAt({320, 500}, 60), o).pixels, 0);
  EXPECT_EQ(sampleTorso(skin, grey, roi, headAt({320, 100}, 0), o).pixels, 0);
}

TEST(ShirtSkin, SkinDarkerThanASkinColouredChestIsCloth) {
  const DetectorOptions o;  // 1.3 x the chest, half of it skin, below 0.8 of the face
  TorsoSample shirt;
  shirt.pixels = 1000;
  shirt.skinFraction = 0.9f;
  shirt.skinLuma = 70;
  EXPECT_FLOAT_EQ(clothLumaBelow(shirt, 140, o), 91);
  TorsoSample bareChest = shirt;  // little skin: a shirt of another colour
  bareChest.skinFraction = 0.3f;
  EXPECT_EQ(clothLumaBelow(bareChest, 140, o), 0);
  TorsoSample bright = shirt;  // as bright as the face: no telling it from a hand
  bright.skinLuma = 120;
  EXPECT_EQ(clothLumaBelow(bright, 140, o), 0);
  EXPECT_EQ(clothLumaBelow(shirt, 0, o), 0);  // no face luma yet
  EXPECT_EQ(clothLumaBelow(TorsoSample{}, 140, o), 0);
  DetectorOptions off = o;
  off.shirtLumaOfTorso = 0;
  EXPECT_EQ(clothLumaBelow(shirt, 140, off), 0);
}

}  // namespace
}  // namespace horopter::detail
