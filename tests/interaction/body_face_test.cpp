// Faces on the body (engine/interaction/body_face.hpp), on hand-made faces:
// below the head at its depth, or much darker than it, a face is none, and
// the head the detector follows is the face on no other's body.
#include <gtest/gtest.h>

#include <vector>

#include "horopter/interaction/detection.hpp"
#include "interaction/body_face.hpp"

namespace horopter::detail {
namespace {

FaceDetection face(cv::Point2f centre, float width, float luma, float disparity,
                   bool inside = true) {
  FaceDetection f;
  f.centre = centre;
  f.width = width;
  f.box = cv::Rect(cvRound(centre.x - width / 2), cvRound(centre.y - width / 2), cvRound(width),
                   cvRound(width));
  f.skinLuma = luma;
  f.disparityPx = disparity;
  f.insideZone = inside;
  return f;
}

// Seed 10486's: the head 55 px wide, skin luma 160, at 45 px of disparity;
// the shirt's "face" 2.5 face widths under it, 76 px, luma 82.
const FaceDetection kHead = face({340, 170}, 55, 160, 45);

TEST(BodyFace, BelowTheHeadAtItsDepthIsOnTheBody) {
  const DetectorOptions o;
  const double w = kHead.width;
  const auto at = [&](double dx, double dy, float disparity) {
    return face(
        {static_cast<float>(kHead.centre.x + dx * w), static_cast<float>(kHead.centre.y + dy * w)},
        60, 160, disparity);
  };
  EXPECT_TRUE(belowAtBodyDepth(at(0, 2.5, 46), kHead, o));
  EXPECT_TRUE(belowAtBodyDepth(at(-1.4, 1.1, 40), kHead, o));  // within 15 % of the depth
  EXPECT_FALSE(belowAtBodyDepth(at(0, 0.9, 45), kHead, o));    // the chin, not the chest
  EXPECT_FALSE(belowAtBodyDepth(at(1.6, 2, 45), kHead, o));    // beside the body
  EXPECT_FALSE(belowAtBodyDepth(at(0, -2, 45), kHead, o));     // above
  EXPECT_FALSE(belowAtBodyDepth(at(0, 2, 36), kHead, o));      // behind: another's
  EXPECT_FALSE(belowAtBodyDepth(at(0, 2, 54), kHead, o));      // in front
  EXPECT_FALSE(belowAtBodyDepth(at(0, 2, 0), kHead, o));       // depth unknown
  DetectorOptions off = o;
  off.bodyFaceBelowFaces = 0;
  EXPECT_FALSE(belowAtBodyDepth(at(0, 2.5, 46), kHead, off));
  DetectorOptions far = o;
  far.bodyFaceBelowFaces = 3;
  EXPECT_FALSE(belowAtBodyDepth(at(0, 2.5, 46), kHead, far));
}

TEST(BodyFace, MuchDarkerThanTheHeadIsOnTheBody) {
  const DetectorOptions o;  // 0.7 of the head's
  EXPECT_TRUE(muchDarkerThanHead(face({100, 100}, 60, 82, 45), 160, o));
  EXPECT_TRUE(muchDarkerThanHead(face({100, 100}, 60, 111, 45), 160, o));
  EXPECT_FALSE(muchDarkerThanHead(face({100, 100}, 60, 113, 45), 160, o));
  EXPECT_FALSE(muchDarkerThanHead(face({100, 100}, 60, 200, 45), 160, o));
  EXPECT_FALSE(muchDarkerThanHead(face({100, 100}, 60, 0, 45), 160, o));  // no skin measured
  EXPECT_FALSE(muchDarkerThanHead(face({100, 100}, 60, 82, 45), 0, o));   // no head
  DetectorOptions off = o;
  off.bodyFaceDarkFraction = 0;
  EXPECT_FALSE(muchDarkerThanHead(face({100, 100}, 60, 82, 45), 160, off));
}

TEST(BodyFace, EitherRuleMakesAFaceOnTheBodyButNotTheHeadItself) {
  const DetectorOptions o;
  const FaceDetection shirt = face({345, 308}, 76, 82, 46);
  EXPECT_TRUE(faceOnTheBody(shirt, kHead, o));
  const FaceDetection darkAside = face({100, 100}, 50, 82, 30);
  EXPECT_TRUE(faceOnTheBody(darkAside, kHead, o));
  const FaceDetection litBelow = face({345, 308}, 76, 150, 46);
  EXPECT_TRUE(faceOnTheBody(litBelow, kHead, o));
  const FaceDetection other = face({500, 180}, 50, 150, 40);
  EXPECT_FALSE(faceOnTheBody(other, kHead, o));
  EXPECT_FALSE(faceOnTheBody(kHead, kHead, o));
  // The head is not on the body of the face under it.
  EXPECT_FALSE(faceOnTheBody(kHead, shirt, o));
}

TEST(BodyFace, TheFollowedHeadIsTheFaceOnNoOthersBody) {
  const DetectorOptions o;
  const FaceDetection shirt = face({345, 308}, 76, 82, 46);  // larger than the head
  const std::vector<FaceDetection> both = {shirt, kHead};
  // The largest face would be the shirt's.
  const FaceDetection* head = followedHead(both, true, 0, o);
  ASSERT_NE(head, nullptr);
  EXPECT_EQ(head->centre, kHead.centre);
  // Without the rules, the largest.
  DetectorOptions off = o;
  off.bodyFaceBelowFaces = 0;
  off.bodyFaceDarkFraction = 0;
  EXPECT_EQ(followedHead(both, true, 0, off)->centre, shirt.centre);
  // The shirt alone: the head's remembered luma keeps it out.
  const std::vector<FaceDetection> alone = {shirt};
  EXPECT_EQ(followedHead(alone, true, 160, o), nullptr);
  EXPECT_EQ(followedHead(alone, true, 0, o)->centre, shirt.centre);
  // Two people: the larger, each on the other's body in neither rule.
  const FaceDetection other = face({520, 180}, 60, 150, 47);
  const std::vector<FaceDetection> two = {kHead, other};
  EXPECT_EQ(followedHead(two, true, 160, o)->centre, other.centre);
  // The region follows faces inside the zone only; the full image any.
  const std::vector<FaceDetection> outside = {face({340, 170}, 55, 160, 45, false)};
  EXPECT_EQ(followedHead(outside, true, 0, o), nullptr);
  EXPECT_NE(followedHead(outside, false, 0, o), nullptr);
}

}  // namespace
}  // namespace horopter::detail
