// Detection on rendered frames of the synthetic scene, with its exact zone
// as the mask: inside the region only the zone's faces and hands, over the
// full image the distractor too; and bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "horopter/detection.hpp"
#include "horopter/error.hpp"
#include "horopter/synthetic_scene.hpp"

namespace horopter {
namespace {

bool texturesPresent() {
  for (const synth::TextureSource& t : synth::textureSources())
    if (t.name == "astronaut" && !t.found) return false;
  return std::filesystem::exists(kDefaultFaceCascade);
}

Frame renderedFrame(int index) {
  synth::SyntheticScene scene(synth::SceneOptions{});
  synth::SyntheticFrame f = scene.render(index);
  Frame frame;
  frame.index = index;
  frame.left = f.left;
  frame.right = f.right;
  frame.mask = f.truth.inside.clone();
  frame.truth = f.truth;
  return frame;
}

bool near(cv::Point2f a, cv::Point2f b, double tolerance) {
  return std::hypot(double(a.x - b.x), double(a.y - b.y)) <= tolerance;
}

TEST(Detection, RegionFindsTheFaceInsideTheZoneOnly) {
  if (!texturesPresent())
    GTEST_SKIP() << "opencv-data or python3-skimage missing (scripts/setup.sh)";
  const Frame frame = renderedFrame(100);
  const auto& truth = std::any_cast<const synth::FrameTruth&>(frame.truth);
  const synth::PersonTruth& main = truth.people[0];
  ASSERT_TRUE(main.insideZone && main.visible);
  Detector detector(DetectorOptions{});
  const Detections d = detector.detect(frame);
  ASSERT_FALSE(d.faces.empty());
  for (const FaceDetection& f : d.faces) {
    EXPECT_TRUE(f.insideZone);
    EXPECT_TRUE(near(f.centre, main.head2d, 0.5 * main.faceWidthPx)) << f.box;
  }
  for (const HandDetection& h : d.hands) {
    EXPECT_TRUE(h.insideZone);
    EXPECT_FALSE(near(h.centroid, main.head2d, 0.4 * main.faceWidthPx)) << "the face is not a hand";
  }
  EXPECT_LT(d.searchedPixels, frame.left.total() / 2) << "the region is smaller than the image";
}

TEST(Detection, FullImageSeesMoreThanTheZone) {
  if (!texturesPresent())
    GTEST_SKIP() << "opencv-data or python3-skimage missing (scripts/setup.sh)";
  const Frame frame = renderedFrame(100);
  DetectorOptions region, full;
  full.scope = DetectionScope::FullImage;
  const Detections r = Detector(region).detect(frame);
  const Detections f = Detector(full).detect(frame);
  EXPECT_EQ(f.searchedPixels, static_cast<std::int64_t>(frame.left.total()));
  // The skin-coloured furniture and posters, and the distractor, are outside the zone.
  EXPECT_GT(f.hands.size(), r.hands.size());
  bool outside = false;
  for (const HandDetection& h : f.hands)
    outside |= !h.insideZone;
  EXPECT_TRUE(outside);
}

// Between full searches the cascade looks only around the previous frame's
// faces: the next frames still find the face where a full search does.
TEST(Detection, FollowingFindsTheFaceAFullSearchFinds) {
  if (!texturesPresent())
    GTEST_SKIP() << "opencv-data or python3-skimage missing (scripts/setup.sh)";
  DetectorOptions followOptions;
  followOptions.fullSearchEvery = 5;
  Detector following(followOptions), full(DetectorOptions{});
  for (int index = 100; index < 104; ++index) {
    const Frame frame = renderedFrame(index);
    const Detections a = following.detect(frame), b = full.detect(frame);
    ASSERT_FALSE(b.faces.empty()) << "frame " << index;
    ASSERT_EQ(a.faces.size(), b.faces.size()) << "frame " << index;
    for (std::size_t i = 0; i < a.faces.size(); ++i)
      EXPECT_TRUE(near(a.faces[i].centre, b.faces[i].centre, 0.25 * b.faces[i].width))
          << "frame " << index << ": " << a.faces[i].box << " vs " << b.faces[i].box;
  }
}

TEST(Detection, BadInputIsAnError) {
  if (!std::filesystem::exists(kDefaultFaceCascade)) GTEST_SKIP() << "opencv-data missing";
  DetectorOptions o;
  o.faceCascade = "/nonexistent/cascade.xml";
  EXPECT_THROW(Detector{o}, Error);
  o = DetectorOptions{};
  o.scaleFactor = 1.0;
  EXPECT_THROW(Detector{o}, Error);
  o = DetectorOptions{};
  o.fullSearchEvery = 0;
  EXPECT_THROW(Detector{o}, Error);
  Detector detector(DetectorOptions{});
  Frame frame;
  frame.left = cv::Mat(48, 64, CV_8UC3, cv::Scalar::all(90));
  EXPECT_THROW(detector.detect(frame), Error) << "the region needs the mask";
  frame.mask = cv::Mat(10, 10, CV_8UC1, cv::Scalar(0));
  EXPECT_THROW(detector.detect(frame), Error) << "mask of another size";
  frame.mask = cv::Mat(48, 64, CV_8UC1, cv::Scalar(0));
  EXPECT_TRUE(detector.detect(frame).faces.empty()) << "an empty zone holds nothing";
}

}  // namespace
}  // namespace horopter
