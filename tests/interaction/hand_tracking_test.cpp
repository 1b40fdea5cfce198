// The tracker's choice of hand candidates on hand-made detections: a hand's
// track keeps to its side of the head, slivers (thin, or not where their
// disparity says) are not hands, a track on a speck moves to the whole hand,
// and the head follows its skin blob when the face is missed.
#include <gtest/gtest.h>

#include <cmath>

#include <functional>
#include <iterator>
#include <memory>
#include <optional>
#include <vector>

#include "hand_candidate.hpp"
#include "horopter/app/frame.hpp"
#include "horopter/core/error.hpp"
#include "horopter/interaction/head_control.hpp"
#include "horopter/interaction/tracking.hpp"

namespace horopter {
namespace {

constexpr float kFace = 60;  // face width, px
const cv::Point2f kHead(320, 120);

HandDetection hand(cv::Point2f at, float radiusPx = 12, float agreement = 1, int areaPx = 0) {
  return testing::handCandidate(at, radiusPx, agreement, areaPx);
}

// The tracker on a frame that carries its detections, as the tracking stage runs it.
TrackingState updateWith(BodyTracker& tracker, const Frame& frame, BodySample& body) {
  return tracker.update(frame, *frame.detections, body);
}

Frame frameWith(std::int64_t index, std::vector<HandDetection> hands) {
  auto d = std::make_shared<Detections>();
  FaceDetection f;
  f.centre = kHead;
  f.width = kFace;
  f.box = cv::Rect(cvRound(kHead.x - kFace / 2), cvRound(kHead.y - kFace / 2), cvRound(kFace),
                   cvRound(kFace));
  f.insideZone = true;
  d->faces.push_back(f);
  d->hands = std::move(hands);
  Frame frame;
  frame.index = index;
  frame.detections = d;
  return frame;
}

TrackerOptions immediateElection() {
  TrackerOptions o;
  o.election.electS = 0;
  return o;
}

// The person's left hand is on the image's right of the head.
const cv::Point2f kLeftRest(kHead.x + 1.4f * kFace, kHead.y + 4.3f * kFace);
const cv::Point2f kRightRest(kHead.x - 1.4f * kFace, kHead.y + 4.3f * kFace);

bool near(cv::Point2f a, cv::Point2f b, float tolerance = 3) {
  return cv::norm(a - b) <= tolerance;
}

TEST(HandTracking, BothHandsStartOnTheirOwnSides) {
  BodyTracker tracker(immediateElection());
  BodySample body;
  updateWith(tracker, frameWith(0, {hand(kLeftRest), hand(kRightRest)}), body);
  ASSERT_TRUE(body.godfather);
  ASSERT_TRUE(body.leftHand.tracked && body.rightHand.tracked);
  EXPECT_TRUE(near(body.leftHand.image, kLeftRest));
  EXPECT_TRUE(near(body.rightHand.image, kRightRest));
}

// A hand that disappears does not jump to the other side of the body, even
// to a candidate inside its gate: the left hand's track coasts instead of
// taking a candidate far on the image's left.
TEST(HandTracking, AHandsTrackDoesNotCrossToTheOtherSide) {
  TrackerOptions o = immediateElection();
  o.reacquireFaceWidths = 10;  // everything would be within reach
  o.maxHandStepFaceWidths = 10;
  BodyTracker tracker(o);
  BodySample body;
  // The left hand rests just right of the head's vertical.
  const cv::Point2f left(kHead.x + 0.3f * kFace, kHead.y + 3 * kFace);
  updateWith(tracker, frameWith(0, {hand(left), hand(kRightRest)}), body);
  ASSERT_TRUE(near(body.leftHand.image, left));
  // Next frame the left hand is gone; a blob appears a face width left of the head.
  const cv::Point2f across(kHead.x - 1.0f * kFace, kHead.y + 3 * kFace);
  updateWith(tracker, frameWith(1, {hand(across), hand(kRightRest)}), body);
  ASSERT_TRUE(body.leftHand.tracked);
  EXPECT_FALSE(body.leftHand.observed) << "the left hand took a candidate on the right's side";
  EXPECT_GT(body.leftHand.image.x, kHead.x);
  EXPECT_TRUE(near(body.rightHand.image, kRightRest));
}

TEST(HandTracking, ThinSliversAndStereoMismatchesAreNotHands) {
  BodyTracker tracker(immediateElection());
  BodySample body;
  // Only a thin sliver (a hand's area, 3 px thick) where the left hand rests,
  // and a blob whose pixels disagree between the views where the right one
  // rests.
  const HandDetection sliver = hand(kLeftRest, 1.5f, 1, 450);
  updateWith(tracker, frameWith(0, {sliver, hand(kRightRest, 12, 0.3f)}), body);
  EXPECT_FALSE(body.leftHand.tracked);
  EXPECT_FALSE(body.rightHand.tracked);
  // The real hands arrive.
  updateWith(tracker,
             frameWith(1, {sliver, hand(kLeftRest + cv::Point2f(10, 0)), hand(kRightRest, 12, 0.3f),
                           hand(kRightRest + cv::Point2f(0, 8))}),
             body);
  ASSERT_TRUE(body.leftHand.tracked && body.rightHand.tracked);
  EXPECT_TRUE(near(body.leftHand.image, kLeftRest + cv::Point2f(10, 0)));
  EXPECT_TRUE(near(body.rightHand.image, kRightRest + cv::Point2f(0, 8)));
}

// A track that fell onto a speck (small, thin) when its hand outran the gate
// moves to the whole hand, a solid candidate on its side.
// A small candidate (a hand partly outside the zone, or a speck) is a hand
// only where its pixels agree between the views.
TEST(HandTracking, SmallCandidatesNeedStereoAgreement) {
  BodyTracker tracker(immediateElection());
  BodySample body;
  const int small = static_cast<int>(0.03f * kFace * kFace);  // under 0.05 face widths squared
  updateWith(tracker,
             frameWith(0, {hand(kLeftRest, 0.07f * kFace, 0.95f, small),
                           hand(kRightRest, 0.07f * kFace, 0.8f, small)}),
             body);
  EXPECT_TRUE(body.leftHand.tracked) << "agreeing: a hand partly outside the zone";
  EXPECT_FALSE(body.rightHand.tracked) << "80 % agreement is not enough for a small one";
}

TEST(HandTracking, ATrackOnASpeckMovesToTheSolidHand) {
  BodyTracker tracker(immediateElection());
  BodySample body;
  const cv::Point2f speck(kHead.x + 1.2f * kFace, kHead.y + 0.9f * kFace);
  // Only the speck (0.06 face widths squared, radius 0.1) on the left's side.
  const HandDetection small = hand(speck, 0.1f * kFace, 1, static_cast<int>(0.06f * kFace * kFace));
  updateWith(tracker, frameWith(0, {small, hand(kRightRest)}), body);
  ASSERT_TRUE(body.leftHand.tracked);
  ASSERT_TRUE(near(body.leftHand.image, speck));
  // The hand appears far from the speck, beyond any gate.
  const cv::Point2f raised(kHead.x + 3.0f * kFace, kHead.y - 1.0f * kFace);
  updateWith(tracker, frameWith(1, {small, hand(raised), hand(kRightRest)}), body);
  EXPECT_TRUE(near(body.leftHand.image, raised)) << body.leftHand.image;
  EXPECT_TRUE(near(body.rightHand.image, kRightRest));
}

// When the cascade misses the face, the head's track follows the face's
// skin blob instead of coasting away (and the godfather is kept).
TEST(HandTracking, TheHeadFollowsItsSkinBlobWhenTheFaceIsMissed) {
  TrackerOptions o = immediateElection();
  o.coastS = 0.05;  // two frames without the head would drop it
  BodyTracker tracker(o);
  BodySample body;
  updateWith(tracker, frameWith(0, {hand(kLeftRest), hand(kRightRest)}), body);
  ASSERT_TRUE(body.head.tracked);
  for (int i = 1; i <= 6; ++i) {
    Frame f = frameWith(
        i, {hand(kHead + cv::Point2f(0, 6), 0.35f * kFace), hand(kLeftRest), hand(kRightRest)});
    auto d = std::make_shared<Detections>(*f.detections);
    d->faces.clear();
    f.detections = d;
    updateWith(tracker, f, body);
    ASSERT_TRUE(body.godfather && body.head.tracked) << "frame " << i;
    EXPECT_TRUE(body.head.observed);
    EXPECT_TRUE(near(body.head.image, kHead + cv::Point2f(0, 6), 4)) << body.head.image;
  }
  EXPECT_TRUE(near(body.leftHand.image, kLeftRest)) << "the face blob is not a hand";
  EXPECT_TRUE(near(body.rightHand.image, kRightRest));
}

// A hand that jumps out of its gate and reach (an arm stretched out to
// point) onto a candidate too small to move a track at once: the track
// coasts for coastJumpS, then moves there, rather than waiting to be
// dropped.
TEST(HandTracking, ACoastingTrackMovesToTheCandidateOnItsSide) {
  const cv::Point2f pointing(kHead.x - 4.0f * kFace, kHead.y + 0.5f * kFace);
  const HandDetection small =
      hand(pointing, 0.1f * kFace, 1, static_cast<int>(0.06f * kFace * kFace));
  for (const double jumpS : {0.1, 0.0}) {
    TrackerOptions o = immediateElection();
    o.coastJumpS = jumpS;
    BodyTracker tracker(o);
    BodySample body;
    updateWith(tracker, frameWith(0, {hand(kLeftRest), hand(kRightRest)}), body);
    ASSERT_TRUE(near(body.rightHand.image, kRightRest));
    for (int i = 1; i <= 5; ++i) {
      updateWith(tracker, frameWith(i, {hand(kLeftRest), small}), body);
      ASSERT_TRUE(body.rightHand.tracked) << "frame " << i;
      // 30 frames/s: frame 4 is the first more than 0.1 s after the last
      // update (frame 3, exactly 0.1 s, is left out).
      if (i == 3) continue;
      const bool moved = jumpS > 0 && i >= 4;
      EXPECT_EQ(near(body.rightHand.image, pointing), moved)
          << "jump " << jumpS << " frame " << i << " at " << body.rightHand.image;
    }
    EXPECT_TRUE(near(body.leftHand.image, kLeftRest));
  }
}

// The left image and disparity map for the blind-following tests: a random
// background, a textured hand at `hand`, and a disparity of `handDisparity`
// px from x = 100 on (to its left, as on the left of a real pair: none).
void paintViews(Frame& frame, cv::Point2f hand, int handDisparity) {
  cv::Mat grey(480, 640, CV_8UC1);
  cv::RNG background(11);
  background.fill(grey, cv::RNG::UNIFORM, 0, 256);
  cv::Mat look(25, 25, CV_8UC1);
  cv::RNG texture(5);
  texture.fill(look, cv::RNG::UNIFORM, 60, 200);
  look.copyTo(grey(cv::Rect(cvRound(hand.x) - 12, cvRound(hand.y) - 12, 25, 25)));
  frame.leftGrey = grey;
  frame.disparity = cv::Mat(480, 640, CV_16SC1, cv::Scalar(-16));
  frame.disparity.colRange(100, 640).setTo(handDisparity * 16);
}

// A hand that moves left of what the right camera sees (no disparity, so no
// candidate) is followed by its look; with blind following off it coasts.
TEST(HandTracking, AHandWhereStereoIsBlindIsFollowedByItsLook) {
  const float xs[] = {150, 150, 150, 130, 110, 95, 80, 70, 70};
  const int firstBlind = 5;
  for (const bool blind : {true, false}) {
    SCOPED_TRACE(blind ? "blind following on" : "blind following off");
    TrackerOptions o = immediateElection();
    o.rig = RectifiedGeometry{500, 320, 0.12, 240};
    o.maxDisparityPx = 95;
    o.blindFollowS = blind ? 1.0 : 0.0;
    BodyTracker tracker(o);
    BodySample body;
    for (int i = 0; i < static_cast<int>(std::size(xs)); ++i) {
      const cv::Point2f hand(xs[i], 300);
      std::vector<HandDetection> candidates = {::horopter::hand(kLeftRest)};
      if (i < firstBlind) candidates.push_back(::horopter::hand(hand));
      Frame frame = frameWith(i, candidates);
      paintViews(frame, hand, 70);
      updateWith(tracker, frame, body);
      ASSERT_TRUE(body.rightHand.tracked) << "frame " << i;
      if (i < firstBlind) continue;
      EXPECT_EQ(body.rightHand.observed, blind) << "frame " << i;
      if (blind) {
        EXPECT_TRUE(near(body.rightHand.image, hand))
            << "frame " << i << " at " << body.rightHand.image;
      }
    }
  }
}

// A hand that jumps out of the right view in one frame (a pointing arm), far
// beyond the search around its track, is found by its look in the band the
// right view does not see; without the band search it coasts.
TEST(HandTracking, AHandThatJumpsIntoTheBandIsFoundThere) {
  for (const double bandFaces : {3.0, 0.0}) {
    SCOPED_TRACE(bandFaces > 0 ? "band searched" : "band not searched");
    TrackerOptions o = immediateElection();
    o.rig = RectifiedGeometry{500, 320, 0.12, 240};
    o.maxDisparityPx = 95;
    o.bandSearchFaces = bandFaces;
    BodyTracker tracker(o);
    BodySample body;
    for (int i = 0; i < 7; ++i) {
      const bool jumped = i >= 4;
      const cv::Point2f hand(jumped ? 60.0f : 200.0f, 300);
      std::vector<HandDetection> candidates = {::horopter::hand(kLeftRest)};
      if (!jumped) candidates.push_back(::horopter::hand(hand));
      Frame frame = frameWith(i, candidates);
      paintViews(frame, hand, 70);
      updateWith(tracker, frame, body);
      ASSERT_TRUE(body.rightHand.tracked) << "frame " << i;
      if (!jumped) continue;
      EXPECT_EQ(body.rightHand.observed, bandFaces > 0) << "frame " << i;
      EXPECT_EQ(near(body.rightHand.image, hand), bandFaces > 0)
          << "frame " << i << " at " << body.rightHand.image;
    }
  }
}

// Blind following needs the front end to have found no depth there: a hand
// missed where the disparity is valid coasts, whatever its last disparity.
TEST(HandTracking, AHandMissedWhereStereoSeesIsNotFollowedByItsLook) {
  TrackerOptions o = immediateElection();
  o.rig = RectifiedGeometry{500, 320, 0.12, 240};
  o.maxDisparityPx = 95;
  BodyTracker tracker(o);
  BodySample body;
  const cv::Point2f hand(200, 300);
  for (int i = 0; i < 4; ++i) {
    std::vector<HandDetection> candidates = {::horopter::hand(kLeftRest)};
    if (i < 2) candidates.push_back(::horopter::hand(hand));
    Frame frame = frameWith(i, candidates);
    paintViews(frame, hand, 90);  // near the range's end, but measured
    updateWith(tracker, frame, body);
    ASSERT_TRUE(body.rightHand.tracked) << "frame " << i;
    EXPECT_EQ(body.rightHand.observed, i < 2) << "frame " << i;
  }
}

// With the head's pose at capture, the tracks move with the image when the
// head turns: the hands' candidates, moved by the turn, stay theirs.
TEST(HandTracking, TracksMoveWithTheImageWhenTheHeadTurns) {
  const RectifiedGeometry rig{500, 320, 0.12, 240};
  const hw::HeadAngles ahead{0, 0, 0.06}, turned{0.3, 0, 0.06};
  const auto moved = [&](cv::Point2f p) { return pixelAfterHeadTurn(p, 1.5, ahead, turned, rig); };
  ASSERT_GT(cv::norm(moved(kRightRest) - kRightRest), 2.0 * kFace) << "beyond a hand's step";
  for (const bool follow : {true, false}) {
    SCOPED_TRACE(follow ? "with the capture pose" : "without it");
    TrackerOptions o = immediateElection();
    o.rig = rig;
    if (follow)
      o.capturePose = [&](const StereoFrame& f) -> std::optional<hw::HeadAngles> {
        return f.index < 3 ? ahead : turned;
      };
    BodyTracker tracker(o);
    BodySample body;
    for (int i = 0; i < 5; ++i) {
      const bool turnedNow = i >= 3;
      const auto at = [&](cv::Point2f p) { return turnedNow ? moved(p) : p; };
      // Not solid (a track on none would move to a solid one at once).
      Frame frame =
          frameWith(i, {::horopter::hand(at(kLeftRest), 8), ::horopter::hand(at(kRightRest), 8)});
      auto detections = std::make_shared<Detections>(*frame.detections);
      detections->faces[0].centre = at(kHead);
      frame.detections = detections;
      updateWith(tracker, frame, body);
      ASSERT_TRUE(body.godfather) << "frame " << i;
      EXPECT_EQ(body.rightHand.observed && near(body.rightHand.image, at(kRightRest)),
                follow || !turnedNow)
          << "frame " << i << " at " << body.rightHand.image;
    }
  }
}

TEST(HandTracking, BadOptionsAreErrors) {
  // Each entry spoils one option of the defaults.
  const std::vector<std::function<void(TrackerOptions&)>> spoilers = {
      [](TrackerOptions& o) { o.minHandRadiusFaces = -1; },
      [](TrackerOptions& o) { o.crossFaceWidths = -0.1; },
      [](TrackerOptions& o) { o.minStereoAgreement = 1.5; },
      [](TrackerOptions& o) { o.headBlobFaceWidths = -1; },
      [](TrackerOptions& o) { o.coastJumpS = -0.1; },
      [](TrackerOptions& o) { o.blindFollowS = -1; },
      [](TrackerOptions& o) { o.blindValidFraction = 1.5; },
      [](TrackerOptions& o) { o.blindPatchFaces = 0; },
      [](TrackerOptions& o) { o.blindMinScore = 2; },
      [](TrackerOptions& o) { o.maxDisparityPx = -1; },
      [](TrackerOptions& o) { o.minHandLumaOfFace = std::nan(""); },
      [](TrackerOptions& o) { o.pinnedDisparityFraction = 1.5; },
  };
  for (std::size_t i = 0; i < spoilers.size(); ++i) {
    TrackerOptions o;
    spoilers[i](o);
    EXPECT_THROW(BodyTracker{o}, Error) << "bad option #" << i;
  }
}

}  // namespace
}  // namespace horopter
