// The synthetic scene's people: 2-D truth is the projection of the 3-D truth,
// the main person walks into the zone and performs the six movements, the
// distractor stays outside, and the rendered faces fire a Haar cascade.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>
#include <opencv2/objdetect.hpp>

#include <cmath>
#include <filesystem>
#include <set>

#include "horopter/sim/synthetic_scene.hpp"

namespace horopter::synth {
namespace {

cv::Point2f project(const SyntheticScene& s, const cv::Point3f& p) {
  // Rig frame to the left image: the left camera sits at x = -B/2.
  const double f = s.focalPx();
  return {static_cast<float>(s.cx() + f * (p.x + 0.5 * s.baselineM()) / p.z),
          static_cast<float>(s.cy() + f * p.y / p.z)};
}

TEST(SyntheticPeople, TwoDimensionalTruthIsTheProjectionOfTheThreeDimensional) {
  SyntheticScene s(SceneOptions{});
  s.commandHead({0.1, 0.05, 0.07});
  for (int index : {0, 40, 100}) {
    const FrameTruth t = s.render(index).truth;
    ASSERT_EQ(t.people.size(), 2u);
    for (const PersonTruth& p : t.people) {
      for (auto [p3, p2] : {std::pair{p.head3d, p.head2d}, std::pair{p.leftHand3d, p.leftHand2d},
                            std::pair{p.rightHand3d, p.rightHand2d}}) {
        const cv::Point2f q = project(s, p3);
        EXPECT_NEAR(q.x, p2.x, 0.01) << "person " << p.id << " frame " << index;
        EXPECT_NEAR(q.y, p2.y, 0.01) << "person " << p.id << " frame " << index;
      }
      // The head's disparity truth at its centre matches its 3-D depth
      // (the surface is in front of the centre by at most the head's depth).
      if (p.visible) {
        const int x = static_cast<int>(std::lround(p.head2d.x));
        const int y = static_cast<int>(std::lround(p.head2d.y));
        const double z = 16 * s.focalPx() * s.baselineM() / t.disparity.at<std::int16_t>(y, x);
        EXPECT_LT(z, p.head3d.z);
        EXPECT_GT(z, p.head3d.z - 0.15);
      }
    }
  }
}

TEST(SyntheticPeople, MainPersonWalksInAndPerformsTheSixMovements) {
  SceneOptions o;
  o.width = 160;
  o.height = 120;
  SyntheticScene s(o);
  EXPECT_FALSE(s.render(0).truth.people[0].insideZone) << "starts outside the zone";
  std::set<Movement> seen;
  bool distractorInside = false;
  for (int i = 0; i < 420; i += 3) {
    const FrameTruth t = s.render(i).truth;
    if (t.people[0].insideZone && t.people[0].visible) seen.insert(t.people[0].movement);
    distractorInside |= t.people[1].insideZone;
  }
  EXPECT_FALSE(distractorInside);
  for (Movement m : {Movement::Circle, Movement::Pointing, Movement::WaveLeft, Movement::WaveRight,
                     Movement::SagittalWave, Movement::ByeBye})
    EXPECT_TRUE(seen.count(m)) << movementName(m) << " never performed inside the zone";
}

TEST(SyntheticPeople, PeopleDifferBySeed) {
  // Height, speed, amplitude and handedness come from the seed.
  std::set<float> heights;
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    SceneOptions o;
    o.width = 160;
    o.height = 120;
    o.seed = seed;
    SyntheticScene s(o);
    heights.insert(s.render(200).truth.people[0].head3d.y);
  }
  EXPECT_EQ(heights.size(), 4u);
}

TEST(SyntheticPeople, FacesFireTheHaarCascade) {
  if (!std::filesystem::exists(HOROPTER_HAAR_FACE))
    GTEST_SKIP() << HOROPTER_HAAR_FACE << " missing (install opencv-data: scripts/setup.sh)";
  for (const TextureSource& t : textureSources())
    if (t.name == "astronaut" && !t.found)
      GTEST_SKIP() << t.path << " missing (install python3-skimage: scripts/setup.sh)";
  cv::CascadeClassifier cascade(HOROPTER_HAAR_FACE);
  ASSERT_FALSE(cascade.empty());
  SyntheticScene s(SceneOptions{});
  int frames = 0, found = 0;
  for (int index : {60, 100, 140}) {
    const SyntheticFrame f = s.render(index);
    const PersonTruth& p = f.truth.people[0];
    ASSERT_TRUE(p.visible && p.insideZone);
    cv::Mat grey;
    cv::cvtColor(f.left, grey, cv::COLOR_BGR2GRAY);
    std::vector<cv::Rect> faces;
    cascade.detectMultiScale(grey, faces, 1.1, 3, 0, cv::Size(24, 24));
    ++frames;
    for (const cv::Rect& r : faces)
      if (r.contains(cv::Point(cvRound(p.head2d.x), cvRound(p.head2d.y))) &&
          std::abs(r.width - p.faceWidthPx) < 0.6 * p.faceWidthPx) {
        ++found;
        break;
      }
  }
  EXPECT_EQ(found, frames) << "the main person's face should be detected in every frame";
}

}  // namespace
}  // namespace horopter::synth
