// Offline determinism of the closed loop: the same trial with 1 and 4 frames
// in flight gives the same tracks and head commands on every frame.
#include <gtest/gtest.h>

#include <filesystem>

#include "horopter/eval/tracking_eval.hpp"

namespace horopter {
namespace {

struct Record {
  bool godfather;
  cv::Point2f head, left, right;
  double pan, tilt;
};

std::vector<Record> run(int inFlight) {
  TrialOptions o;
  o.seed = 5;
  o.frames = 110;
  o.width = 320;
  o.height = 240;
  o.inFlight = inFlight;
  o.tracker.election.electS = 0.3;  // elected early: head commands within few frames
  std::vector<Record> records;
  runTrackingTrial(o, DetectionScope::HoropterRegion, {}, [&](const TrialFrame& t) {
    const BodySample& b = t.frame.body;
    records.push_back({b.godfather, b.head.image, b.leftHand.image, b.rightHand.image,
                       t.truth.head.pan, t.truth.head.tilt});
  });
  return records;
}

TEST(TrackingTrial, SameResultsWhateverTheFramesInFlight) {
  if (!std::filesystem::exists(kDefaultFaceCascade)) GTEST_SKIP() << "opencv-data missing";
  const std::vector<Record> a = run(1), b = run(4);
  ASSERT_EQ(a.size(), 110u);
  ASSERT_EQ(b.size(), a.size());
  bool elected = false, turned = false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].godfather, b[i].godfather) << "frame " << i;
    EXPECT_EQ(a[i].head, b[i].head) << "frame " << i;
    EXPECT_EQ(a[i].left, b[i].left) << "frame " << i;
    EXPECT_EQ(a[i].right, b[i].right) << "frame " << i;
    EXPECT_EQ(a[i].pan, b[i].pan) << "frame " << i;
    EXPECT_EQ(a[i].tilt, b[i].tilt) << "frame " << i;
    elected |= a[i].godfather;
    turned |= a[i].pan != 0 || a[i].tilt != 0;
  }
  EXPECT_TRUE(elected) << "the test should reach an election";
  EXPECT_TRUE(turned) << "the test should move the head";
}

}  // namespace
}  // namespace horopter
