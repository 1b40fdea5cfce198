// The renderer draws a frame incrementally when the head has not moved since
// the last one (only where people's parts changed): such frames must be the
// same, bit for bit, as frames rendered on their own.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include <string>

#include "horopter/core/error.hpp"
#include "horopter/sim/synthetic_scene.hpp"

namespace horopter::synth {
namespace {

bool sameMat(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0;
}

void expectSameFrame(const SyntheticFrame& a, const SyntheticFrame& b, const std::string& what) {
  EXPECT_TRUE(sameMat(a.left, b.left)) << what;
  EXPECT_TRUE(sameMat(a.right, b.right)) << what;
  EXPECT_TRUE(sameMat(a.truth.disparity, b.truth.disparity)) << what;
  EXPECT_TRUE(sameMat(a.truth.inside, b.truth.inside)) << what;
  EXPECT_TRUE(sameMat(a.truth.occluded, b.truth.occluded)) << what;
  ASSERT_EQ(a.truth.people.size(), b.truth.people.size()) << what;
  for (std::size_t i = 0; i < a.truth.people.size(); ++i) {
    EXPECT_EQ(a.truth.people[i].visible, b.truth.people[i].visible) << what;
    EXPECT_EQ(a.truth.people[i].head2d, b.truth.people[i].head2d) << what;
  }
}

SceneOptions smallScene() {
  SceneOptions o;
  o.width = 320;
  o.height = 240;
  o.seed = 4;
  o.skinClutter = true;
  return o;
}

// Frames 40-63 span the end of the main person's walk and the start of the
// first movement; the distractor sways all along.
TEST(SyntheticIncremental, ConsecutiveFramesEqualFramesRenderedAlone) {
  SyntheticScene consecutive(smallScene());
  int compared = 0;
  for (int index = 40; index < 64; ++index) {
    const SyntheticFrame f = consecutive.render(index);
    if (index % 3 != 0) continue;
    SyntheticScene alone(smallScene());
    expectSameFrame(f, alone.render(index), "frame " + std::to_string(index));
    ++compared;
  }
  EXPECT_EQ(compared, 8);
}

// A turn of the head, a change of vergence alone and a jump back in time
// between consecutive renders: each frame still equals one rendered alone.
TEST(SyntheticIncremental, HeadCommandsAndJumpsBetweenFrames) {
  SyntheticScene scene(smallScene());
  const HeadPose still = smallScene().initialHead;
  HeadPose turned = still;
  turned.pan = 0.08;
  HeadPose verged = still;
  verged.vergence = 0.09;
  struct Step {
    int index;
    HeadPose head;
  };
  const Step steps[] = {{100, still},  {101, still},  {102, turned}, {103, turned},
                        {104, verged}, {105, verged}, {30, verged},  {31, still}};
  for (const Step& s : steps) {
    scene.commandHead(s.head);
    const SyntheticFrame f = scene.render(s.index);
    SyntheticScene alone(smallScene());
    alone.commandHead(s.head);
    expectSameFrame(f, alone.render(s.index), "frame " + std::to_string(s.index));
  }
}

// The rows of a frame split over OpenCV's threads or drawn on the calling
// thread alone: the same frames. A negative count is refused.
TEST(SyntheticIncremental, ThreadCountDoesNotChangeFrames) {
  SceneOptions one = smallScene();
  one.threads = 1;
  SyntheticScene serial(one), parallel(smallScene());
  for (int index = 50; index < 56; ++index)
    expectSameFrame(serial.render(index), parallel.render(index), "frame " + std::to_string(index));
  SceneOptions bad = smallScene();
  bad.threads = -1;
  EXPECT_THROW(SyntheticScene{bad}, Error);
}

// Without per-pixel truth, the same images and people's truth, frame after
// frame and across head turns, and empty truth maps.
TEST(SyntheticIncremental, WithoutPixelTruthTheImagesAreTheSame) {
  SceneOptions without = smallScene();
  without.pixelTruth = false;
  SyntheticScene fast(without), full(smallScene());
  HeadPose turned = smallScene().initialHead;
  turned.pan = -0.05;
  for (int index = 60; index < 66; ++index) {
    if (index == 63) {
      fast.commandHead(turned);
      full.commandHead(turned);
    }
    const SyntheticFrame a = fast.render(index), b = full.render(index);
    const std::string what = "frame " + std::to_string(index);
    EXPECT_TRUE(sameMat(a.left, b.left)) << what;
    EXPECT_TRUE(sameMat(a.right, b.right)) << what;
    EXPECT_TRUE(a.truth.disparity.empty() && a.truth.inside.empty() && a.truth.occluded.empty())
        << what;
    EXPECT_FALSE(b.truth.disparity.empty()) << what;
    ASSERT_EQ(a.truth.people.size(), b.truth.people.size()) << what;
    for (std::size_t i = 0; i < a.truth.people.size(); ++i) {
      EXPECT_EQ(a.truth.people[i].insideZone, b.truth.people[i].insideZone) << what;
      EXPECT_EQ(a.truth.people[i].head2d, b.truth.people[i].head2d) << what;
      EXPECT_EQ(a.truth.people[i].leftHand3d, b.truth.people[i].leftHand3d) << what;
    }
  }
}

}  // namespace
}  // namespace horopter::synth
