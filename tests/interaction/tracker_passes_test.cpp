// The tracker's passes one by one (engine/interaction/tracker_passes.hpp), on
// hand-made candidates and tracks: each pass's rule holds, and its limits
// are where the options put them.
#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "hand_candidate.hpp"
#include "horopter/interaction/tracking.hpp"
#include "interaction/blind_follow.hpp"
#include "interaction/tracker_passes.hpp"

namespace horopter::detail {
namespace {

constexpr double kFw = 60;  // face width, px
const cv::Point2f kHead(320, 120);

HandDetection cand(cv::Point2f at, float radiusPx = 12, float agreement = 1, int areaPx = 0) {
  return testing::handCandidate(at, radiusPx, agreement, areaPx);
}

// A hand frame at time t over all of `dets` (they must outlive it).
HandFrame handFrame(const std::vector<HandDetection>& dets, double t = 1.0) {
  HandFrame f;
  f.head = kHead;
  f.fw = kFw;
  f.t = t;
  for (const HandDetection& d : dets)
    f.candidates.push_back(&d);
  f.taken.assign(f.candidates.size(), false);
  return f;
}

HandTrack handAt(cv::Point2f at, double t, const TrackerOptions& o = {}) {
  HandTrack h;
  h.track.emplace(at, t, o.hands);
  h.lastSeen = at;
  return h;
}

bool same(cv::Point2f a, cv::Point2f b) {
  return a.x == b.x && a.y == b.y;
}

std::vector<const HandDetection*> pointers(const std::vector<HandDetection>& dets) {
  std::vector<const HandDetection*> p;
  for (const HandDetection& d : dets)
    p.push_back(&d);
  return p;
}

// ---- nearestFreeCandidate -------------------------------------------------

TEST(TrackerPasses, NearestFreeCandidateSkipsTakenAndIneligible) {
  const std::vector<HandDetection> dets = {cand({10, 0}), cand({20, 0}), cand({30, 0})};
  const auto c = pointers(dets);
  const auto all = [](std::size_t) { return true; };
  EXPECT_EQ(nearestFreeCandidate(c, {false, false, false}, all, {0, 0}), 0u);
  EXPECT_EQ(nearestFreeCandidate(c, {true, false, false}, all, {0, 0}), 1u);
  EXPECT_EQ(
      nearestFreeCandidate(c, {true, false, false}, [](std::size_t j) { return j != 1; }, {0, 0}),
      2u);
  EXPECT_FALSE(nearestFreeCandidate(c, {true, true, true}, all, {0, 0}));
  EXPECT_FALSE(nearestFreeCandidate({}, {}, all, {0, 0}));
}

TEST(TrackerPasses, NearestFreeCandidateKeepsWithinTheMaximumDistance) {
  const std::vector<HandDetection> dets = {cand({10, 0}), cand({20, 0})};
  const auto c = pointers(dets);
  const auto all = [](std::size_t) { return true; };
  EXPECT_FALSE(nearestFreeCandidate(c, {false, false}, all, {0, 0}, 9.9));
  EXPECT_EQ(nearestFreeCandidate(c, {false, false}, all, {0, 0}, 10.0), 0u);  // inclusive
  EXPECT_FALSE(nearestFreeCandidate(c, {true, false}, all, {0, 0}, 19.0));
  EXPECT_EQ(nearestFreeCandidate(c, {true, false}, all, {0, 0}, 20.0), 1u);
}

TEST(TrackerPasses, NearestFreeCandidateBreaksTiesByIndex) {
  // Three candidates 5 px from the origin, and a farther one first.
  const std::vector<HandDetection> dets = {cand({9, 0}), cand({3, 4}), cand({0, 5}), cand({-5, 0})};
  const auto c = pointers(dets);
  const auto all = [](std::size_t) { return true; };
  const std::vector<bool> free(4, false);
  EXPECT_EQ(nearestFreeCandidate(c, free, all, {0, 0}), 1u);
  EXPECT_EQ(nearestFreeCandidate(c, free, all, {0, 0}, 100.0), 1u);
  EXPECT_EQ(nearestFreeCandidate(c, free, all, {0, 0}, 100.0, Ties::HighestIndex), 3u);
  EXPECT_EQ(nearestFreeCandidate(c, free, all, {0, 0}, std::nullopt, Ties::HighestIndex), 3u);
}

TEST(TrackerPasses, AHandsSideReachesCrossFaceWidthsAcrossTheHead) {
  const TrackerOptions o;  // crossFaceWidths 0.6: 36 px
  // The person's left hand (0) is on the image's right.
  EXPECT_TRUE(onHandSide(0, {kHead.x + 100, 300}, kHead, kFw, o));
  EXPECT_TRUE(onHandSide(0, {kHead.x - 36, 300}, kHead, kFw, o));
  EXPECT_FALSE(onHandSide(0, {kHead.x - 37, 300}, kHead, kFw, o));
  EXPECT_TRUE(onHandSide(1, {kHead.x + 36, 300}, kHead, kFw, o));
  EXPECT_FALSE(onHandSide(1, {kHead.x + 37, 300}, kHead, kFw, o));
}

// ---- clock and prediction ---------------------------------------------------

TEST(TrackerPasses, FrameTimeIsIndexOverRateOrCaptureTimeSinceTheFirst) {
  TrackerOptions o;
  o.framesPerSecond = 30;
  FrameClock clock;
  StereoFrame frame;
  frame.index = 45;
  frame.captured = SteadyClock::time_point(std::chrono::seconds(7));
  EXPECT_DOUBLE_EQ(frameTimeS(frame, o, clock), 1.5);
  EXPECT_FALSE(clock.haveStart);
  o.captureTime = true;
  EXPECT_DOUBLE_EQ(frameTimeS(frame, o, clock), 0.0);
  frame.captured += std::chrono::milliseconds(500);
  EXPECT_DOUBLE_EQ(frameTimeS(frame, o, clock), 0.5);
}

TEST(TrackerPasses, PredictMovesEveryTrackToTheFramesTime) {
  SubjectTracks s;
  s.head.emplace(kHead, 0.0, TrackerOptions{}.head);
  s.hands[1] = handAt({200, 300}, 0.0);
  predictTracks(s, 0.25);
  EXPECT_DOUBLE_EQ(s.head->timeS(), 0.25);
  EXPECT_FALSE(s.hands[0].track);
  EXPECT_DOUBLE_EQ(s.hands[1].track->timeS(), 0.25);
}

// ---- head association and election -------------------------------------------

FaceDetection face(cv::Point2f at, float width, bool inside = true) {
  FaceDetection f;
  f.centre = at;
  f.width = width;
  f.insideZone = inside;
  return f;
}

TEST(TrackerPasses, TheHeadTakesTheNearestFaceInItsGate) {
  ConstantVelocityTrack head(kHead, 0.0, TrackerOptions{}.head);
  head.predict(1.0 / 30);
  const std::vector<FaceDetection> faces = {face({600, 120}, 60), face({326, 120}, 60),
                                            face({318, 120}, 60)};
  EXPECT_EQ(nearestFaceInGate(head, faces), &faces[2]);
  EXPECT_EQ(nearestFaceInGate(head, {faces[0]}), nullptr);
}

TEST(TrackerPasses, TheHeadsSkinBlobIsTheLargestRoundBlobNearIt) {
  TrackerOptions o;  // headBlobFaceWidths 0.5: 30 px
  const ConstantVelocityTrack head(kHead, 0.0, o.head);
  const std::vector<HandDetection> blobs = {
      cand({330, 130}, 15, 1, 1200),  // large and round enough
      cand({325, 125}, 20, 1, 2000),  // larger
      cand({400, 120}, 40, 1, 5000),  // too far
      cand({322, 122}, 10, 1, 9000),  // too thin
      cand({318, 118}, 20, 1, 1000),  // too small (under 0.3 * 60^2)
  };
  EXPECT_EQ(headSkinBlob(head, 60, blobs, o), &blobs[1]);
  EXPECT_EQ(headSkinBlob(head, 60, {blobs[2], blobs[3], blobs[4]}, o), nullptr);
  o.headBlobFaceWidths = 0;
  EXPECT_EQ(headSkinBlob(head, 60, blobs, o), nullptr);
}

TEST(TrackerPasses, ANewSubjectIsTheLargestFaceInside) {
  const std::vector<FaceDetection> faces = {face({100, 100}, 50), face({300, 100}, 70, false),
                                            face({500, 100}, 60)};
  EXPECT_EQ(largestFaceInside(faces), &faces[2]);
  EXPECT_EQ(largestFaceInside({faces[1]}), nullptr);
}

TEST(TrackerPasses, HeadAssociationStartsUpdatesFollowsTheBlobOrCoasts) {
  const TrackerOptions o;
  SubjectTracks s;
  Detections det;
  det.faces = {face({300, 100}, 70, false)};
  EXPECT_FALSE(associateHead(s, det, 0.0, o));  // no face inside: no subject
  EXPECT_FALSE(s.head);

  det.faces = {face(kHead, 60)};
  EXPECT_EQ(associateHead(s, det, 0.0, o), std::optional<bool>(true));
  ASSERT_TRUE(s.head);
  EXPECT_TRUE(same(s.head->position(), kHead));
  EXPECT_EQ(s.faceWidth, 60);

  s.head->predict(0.1);
  det.faces = {face({kHead.x + 4, kHead.y}, 64, false)};
  EXPECT_EQ(associateHead(s, det, 0.1, o), std::optional<bool>(false));
  EXPECT_EQ(s.head->lastUpdateS(), 0.1);
  EXPECT_EQ(s.faceWidth, 64);

  s.head->predict(0.2);
  det.faces.clear();
  det.hands = {cand({kHead.x, kHead.y + 10}, 20, 1, 2000)};
  det.hands[0].insideZone = false;
  EXPECT_EQ(associateHead(s, det, 0.2, o), std::optional<bool>(false));
  EXPECT_EQ(s.head->lastUpdateS(), 0.2);
  EXPECT_EQ(s.faceWidth, 64);  // a blob does not measure the face

  s.head->predict(0.3);
  det.hands.clear();
  EXPECT_FALSE(associateHead(s, det, 0.3, o));
  ASSERT_TRUE(s.head);  // coasting
  EXPECT_EQ(s.head->lastUpdateS(), 0.2);
}

TEST(TrackerPasses, ElectionWithoutSubjectOrWithAStaleHeadDropsTheTracks) {
  TrackerOptions o;  // coastS 0.4
  o.election.electS = 0;
  const auto subject = [&](double t) {
    SubjectTracks s;
    s.head.emplace(kHead, t, o.head);
    s.hands[0] = handAt({420, 380}, t);
    s.hands[1] = handAt({220, 380}, t);
    return s;
  };
  {
    GodfatherElection election(o.election);
    SubjectTracks s = subject(0.0);
    EXPECT_EQ(updateElection(election, s, std::nullopt, 0.0, o), ElectionState::None);
    EXPECT_FALSE(s.head || s.hands[0].track || s.hands[1].track);
  }
  {
    GodfatherElection election(o.election);
    SubjectTracks s = subject(0.0);
    EXPECT_EQ(updateElection(election, s, true, 0.0, o), ElectionState::Godfather);
    EXPECT_TRUE(s.head && s.hands[0].track && s.hands[1].track);
    // Missed for longer than coastS: head and hands go, the election stays.
    EXPECT_EQ(updateElection(election, s, std::nullopt, 0.3, o), ElectionState::Godfather);
    EXPECT_TRUE(s.head);
    EXPECT_EQ(updateElection(election, s, std::nullopt, 0.5, o), ElectionState::Godfather);
    EXPECT_FALSE(s.head || s.hands[0].track || s.hands[1].track);
  }
}

// ---- hand candidates -----------------------------------------------------------

TEST(TrackerPasses, ThePlausibilityFilterRejectsEachLimitInTurn) {
  const TrackerOptions o;
  const auto kept = [&](const HandDetection& c) {
    return plausibleHandCandidates({c}, kHead, kFw, o).size() == 1;
  };
  const cv::Point2f at(420, 380);
  EXPECT_TRUE(kept(cand(at)));
  EXPECT_FALSE(kept(cand({330, 150})));  // the face or neck
  EXPECT_TRUE(faceOrNeck({330, 150}, kHead, kFw));
  EXPECT_FALSE(faceOrNeck({330, 200}, kHead, kFw));
  EXPECT_TRUE(kept(cand({330, 200})));                       // below the neck
  EXPECT_FALSE(kept(cand({kHead.x + 300, kHead.y + 400})));  // out of reach (7 faces)
  EXPECT_TRUE(kept(cand({kHead.x + 240, kHead.y + 320})));   // 400 px: in reach
  EXPECT_FALSE(kept(cand(at, 30, 1, 3700)));                 // over 1 squared face
  EXPECT_FALSE(kept(cand(at, 4, 1, 70)));                    // under 0.02 squared faces
  EXPECT_FALSE(kept(cand(at, 2.9f, 1, 300)));                // thinner than 0.05 faces
  EXPECT_TRUE(kept(cand(at, 3.1f, 0.95f, 300)));             // thin but agreeing
  EXPECT_FALSE(kept(cand(at, 12, 0.69f)));                   // views disagree
  EXPECT_TRUE(kept(cand(at, 12, 0.71f)));                    // ... enough agree
  EXPECT_FALSE(kept(cand(at, 5, 0.85f)));                    // small: needs 0.9
  EXPECT_TRUE(kept(cand(at, 5, 0.91f)));                     // ... and has it
  const std::vector<HandDetection> dets = {cand(at), cand({330, 150}), cand({200, 380})};
  const auto c = plausibleHandCandidates(dets, kHead, kFw, o);
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c[0], &dets[0]);
  EXPECT_EQ(c[1], &dets[2]);
}

TEST(TrackerPasses, CandidatesMuchDarkerThanTheFaceAreNotHands) {
  TrackerOptions o;
  const auto kept = [&](float luma, float faceLuma) {
    HandDetection c = cand({420, 380});
    c.meanLuma = luma;
    return plausibleHandCandidates({c}, kHead, kFw, o, faceLuma).size() == 1;
  };
  EXPECT_TRUE(kept(60, 0));     // the face's luma unknown: no limit
  EXPECT_FALSE(kept(60, 150));  // cloth: 0.4 of the face
  EXPECT_FALSE(kept(82, 150));  // just under 0.55
  EXPECT_TRUE(kept(83, 150));
  o.minHandLumaOfFace = 0;
  EXPECT_TRUE(kept(10, 150));
  // The head's association keeps the subject's face luma.
  SubjectTracks s;
  Detections det;
  FaceDetection face;
  face.centre = kHead;
  face.width = kFw;
  face.insideZone = true;
  face.skinLuma = 140;
  det.faces.push_back(face);
  associateHead(s, det, 0.0, o);
  EXPECT_EQ(s.faceLuma, 140.f);
  det.faces[0].skinLuma = 0;  // no skin measured this time: the last is kept
  associateHead(s, det, 0.1, o);
  EXPECT_EQ(s.faceLuma, 140.f);
}

TEST(TrackerPasses, CandidatesPinnedAtTheRangesEndAreNotHands) {
  TrackerOptions o;
  o.maxDisparityPx = 95;
  const auto kept = [&](float disparity) {
    HandDetection c = cand({420, 380});
    c.disparityPx = disparity;
    return plausibleHandCandidates({c}, kHead, kFw, o).size() == 1;
  };
  EXPECT_TRUE(kept(0));  // nothing measured
  EXPECT_TRUE(kept(84));
  EXPECT_TRUE(kept(89.2f));
  EXPECT_FALSE(kept(89.4f));  // 0.94 of 95 = 89.3
  EXPECT_FALSE(kept(93));
  o.pinnedDisparityFraction = 0;
  EXPECT_TRUE(kept(93));
  o.pinnedDisparityFraction = 0.94;
  o.maxDisparityPx = 0;  // the range unknown
  EXPECT_TRUE(kept(93));
}

TEST(TrackerPasses, OnlyAHandLastMeasuredNearTakesAPinnedWholeHand) {
  TrackerOptions o;
  o.maxDisparityPx = 95;
  const auto pinnedAt = [](cv::Point2f at, float radius) {
    HandDetection c = cand(at, radius);
    c.disparityPx = 92;  // pinned: 0.94 of 95 = 89.3
    return c;
  };
  // A whole hand (radius 12 of a 60 px face: solid) 20 px from the right
  // hand's track, and a speck beside it; nothing else.
  const std::vector<HandDetection> dets = {pinnedAt({250, 380}, 12), pinnedAt({245, 385}, 5)};
  const auto run = [&](double disparity, const TrackerOptions& opts, cv::Point2f from) {
    std::array<HandTrack, 2> hands = {HandTrack{}, handAt(from, 1.0)};
    HandFrame f;
    f.head = kHead;
    f.fw = kFw;
    f.t = 1.0;
    f.candidates = plausibleHandCandidates(dets, kHead, kFw, opts, 0, &f.pinned);
    f.taken.assign(f.candidates.size(), false);
    EXPECT_TRUE(f.candidates.empty());  // both refused as pinned
    takePinnedNearHands(hands, f, {0, disparity}, opts);
    return std::make_pair(f, hands);
  };
  // Last measured at 85 px (0.89 of 95): it takes the whole hand, not the speck.
  {
    auto [f, hands] = run(85, o, {230, 380});
    ASSERT_EQ(f.candidates.size(), 1u);
    EXPECT_EQ(f.candidates[0], &dets[0]);
    EXPECT_EQ(f.taken, std::vector<bool>{true});
    EXPECT_EQ(f.steps[1].held, std::optional<std::size_t>(0));
    EXPECT_EQ(f.steps[1].detectedBy, &dets[0]);
    EXPECT_TRUE(same(hands[1].lastSeen, {250, 380}));
  }
  // Last measured at 75 px (a hand at the body's depth): the pinned blob is
  // clutter to it (the wood behind a shoulder), and stays refused.
  {
    auto [f, hands] = run(75, o, {230, 380});
    EXPECT_TRUE(f.candidates.empty());
    EXPECT_FALSE(f.steps[1].updated);
  }
  // Unknown disparity, or the rule off: refused.
  EXPECT_FALSE(run(0, o, {230, 380}).first.steps[1].updated);
  TrackerOptions off = o;
  off.pinnedNearFraction = 0;
  EXPECT_FALSE(run(85, off, {230, 380}).first.steps[1].updated);
  // Too far from the track and from where the hand was last seen (3 face widths).
  EXPECT_FALSE(run(85, o, {70, 380}).first.steps[1].updated);
  // The speck alone is not taken even by a near hand.
  {
    std::array<HandTrack, 2> hands = {HandTrack{}, handAt({240, 385}, 1.0)};
    HandFrame f = handFrame({}, 1.0);
    f.pinned = {&dets[1]};
    takePinnedNearHands(hands, f, {0, 90}, o);
    EXPECT_FALSE(f.steps[1].updated);
  }
  // Not across the head's vertical: the left hand's track is on the image's
  // right, and the whole hand is 70 px left of the head.
  {
    std::array<HandTrack, 2> hands = {handAt({262, 380}, 1.0), HandTrack{}};
    HandFrame f = handFrame({}, 1.0);
    f.pinned = {&dets[0]};
    takePinnedNearHands(hands, f, {90, 0}, o);
    EXPECT_FALSE(f.steps[0].updated);
  }
}

TEST(TrackerPasses, GatedAssignmentIsNearestFirstOneCandidatePerTrack) {
  const TrackerOptions o;
  const double t = 1.0 / 30;
  std::array<HandTrack, 2> hands = {handAt({330, 380}, 0.0), handAt({310, 380}, 0.0)};
  for (HandTrack& h : hands)
    h.track->predict(t);
  // X is 8 px from the right hand's track and 12 from the left's; Y 15 from
  // the left's. Taken track by track, the left hand would take X.
  const std::vector<HandDetection> dets = {cand({345, 380}), cand({318, 380})};
  HandFrame f = handFrame(dets, t);
  assignGated(hands, f, o);
  EXPECT_EQ(f.steps[0].held, std::optional<std::size_t>(0));
  EXPECT_EQ(f.steps[1].held, std::optional<std::size_t>(1));
  EXPECT_TRUE(f.steps[0].updated && f.steps[1].updated);
  EXPECT_EQ(f.steps[1].detectedBy, &dets[1]);
  EXPECT_TRUE(same(hands[1].lastSeen, {318, 380}));
  EXPECT_EQ(f.taken, (std::vector<bool>{true, true}));

  // One candidate, wanted by both: the nearer track takes it, the other none.
  hands = {handAt({330, 380}, 0.0), handAt({310, 380}, 0.0)};
  const std::vector<HandDetection> one = {cand({322, 380})};
  HandFrame g = handFrame(one, 0.0);
  assignGated(hands, g, o);
  EXPECT_EQ(g.steps[0].held, std::optional<std::size_t>(0));
  EXPECT_FALSE(g.steps[1].updated);
  EXPECT_FALSE(g.steps[1].held);
}

TEST(TrackerPasses, GatedAssignmentKeepsToTheSideAndTheStepLimit) {
  TrackerOptions o;
  std::array<HandTrack, 2> hands = {handAt({300, 380}, 0.0), HandTrack{}};
  const std::vector<HandDetection> across = {cand({283, 380})};  // 37 px across the head
  HandFrame f = handFrame(across, 0.0);
  assignGated(hands, f, o);
  EXPECT_FALSE(f.steps[0].updated);
  o.maxHandStepFaceWidths = 0.1;  // 6 px
  const std::vector<HandDetection> step = {cand({310, 380})};
  HandFrame g = handFrame(step, 0.0);
  assignGated(hands, g, o);
  EXPECT_FALSE(g.steps[0].updated);
  o.maxHandStepFaceWidths = 0.2;  // 12 px
  assignGated(hands, g, o);
  EXPECT_TRUE(g.steps[0].updated);
}

TEST(TrackerPasses, StereoIsBlindOnlyWhereTheFrontEndFoundNoDepth) {
  TrackerOptions o;  // band 0.5 faces (30 px), near above 0.85 of the range, valid under 0.5
  o.maxDisparityPx = 95;
  ASSERT_EQ(o.blindTextureless, 0);  // off by default
  const cv::Point2f band(90, 300), middle(300, 300);
  // Left of d + half a face (70 + 30 = 100 px) the right view does not see.
  EXPECT_TRUE(stereoBlindAt(band, 70, 0.1, kFw, o));
  EXPECT_FALSE(stereoBlindAt({101, 300}, 70, 0.1, kFw, o));
  // Nearer than the range: the last disparity above 0.85 of 95 (80.75 px).
  EXPECT_TRUE(stereoBlindAt(middle, 81, 0.1, kFw, o));
  EXPECT_FALSE(stereoBlindAt(middle, 80, 0.1, kFw, o));
  EXPECT_FALSE(stereoBlindAt(middle, 0, 0.1, kFw, o));  // the last disparity unknown
  // Wherever the front end found depth, nothing is blind.
  EXPECT_FALSE(stereoBlindAt(band, 70, 0.5, kFw, o));
  EXPECT_FALSE(stereoBlindAt(middle, 90, 0.6, kFw, o));
  // With blindTextureless, missing depth alone is blindness (a smooth hand
  // in dim light has none, wherever it is).
  o.blindTextureless = 1;
  EXPECT_TRUE(stereoBlindAt(middle, 60, 0.49, kFw, o));
  EXPECT_TRUE(stereoBlindAt(middle, 0, 0.0, kFw, o));
  EXPECT_FALSE(stereoBlindAt(middle, 60, 0.5, kFw, o));
}

TEST(TrackerPasses, TheRightViewsBandIsSearchedOnlyNearItAndWithinItsRows) {
  TrackerOptions o;  // band 0.5 faces (30 px); searched from 3 faces (180 px) right of it
  ASSERT_GT(o.bandSearchFaces, 0);
  const cv::Size image(640, 480);
  // d 70: the band is x < 100; a track at 250 (within 280) searches it, in
  // the rows from the prediction's to the last sighting's, a face either side.
  const std::optional<cv::Rect> w = rightViewBandWindow({250, 300}, {270, 340}, 70, kFw, image, o);
  ASSERT_TRUE(w);
  EXPECT_EQ(*w, cv::Rect(0, 240, 100, 161));
  // Either the prediction or the last sighting near the band will do.
  EXPECT_TRUE(rightViewBandWindow({400, 300}, {280, 300}, 70, kFw, image, o));
  EXPECT_TRUE(rightViewBandWindow({280, 300}, {400, 300}, 70, kFw, image, o));
  EXPECT_FALSE(rightViewBandWindow({281, 300}, {400, 300}, 70, kFw, image, o));
  // The last disparity unknown: no band.
  EXPECT_FALSE(rightViewBandWindow({90, 300}, {90, 300}, 0, kFw, image, o));
  // Rows are clipped to the image.
  const std::optional<cv::Rect> top = rightViewBandWindow({90, 20}, {90, 30}, 70, kFw, image, o);
  ASSERT_TRUE(top);
  EXPECT_EQ(*top, cv::Rect(0, 0, 100, 91));
  // Off.
  o.bandSearchFaces = 0;
  EXPECT_FALSE(rightViewBandWindow({90, 300}, {90, 300}, 70, kFw, image, o));
}

TEST(TrackerPasses, ALookFoundInTheBandMustMatchInLevelAndContrast) {
  cv::Mat grey(200, 200, CV_8UC1, cv::Scalar(128));
  cv::Mat look(21, 21, CV_8UC1);
  cv::RNG texture(5);
  texture.fill(look, cv::RNG::UNIFORM, 90, 170);
  look.copyTo(grey(cv::Rect(40, 40, 21, 21)));
  PatchFollower follower;
  follower.remember(grey, {50, 50}, 21);
  ASSERT_FALSE(follower.empty());
  // The same texture darker and flatter elsewhere: correlation alone takes it.
  cv::Mat dim;
  look.convertTo(dim, CV_8UC1, 0.4, 10);
  grey(cv::Rect(40, 40, 21, 21)).setTo(128);
  dim.copyTo(grey(cv::Rect(140, 140, 21, 21)));
  const cv::Rect everywhere(0, 0, 200, 200);
  const std::optional<cv::Point2f> any = follower.find(grey, {100, 100}, {100, 100}, 90, 0.7);
  ASSERT_TRUE(any);
  EXPECT_TRUE(same(*any, {150, 150}));
  EXPECT_FALSE(follower.findAlikeIn(grey, everywhere, 0.7));
  // The look itself, somewhat brighter (within a quarter), is found.
  cv::Mat brighter;
  look.convertTo(brighter, CV_8UC1, 1.0, 20);
  brighter.copyTo(grey(cv::Rect(100, 20, 21, 21)));
  const std::optional<cv::Point2f> alike = follower.findAlikeIn(grey, everywhere, 0.7);
  ASSERT_TRUE(alike);
  EXPECT_TRUE(same(*alike, {110, 30}));
  // Only centres inside the given box count.
  EXPECT_FALSE(follower.findAlikeIn(grey, cv::Rect(0, 0, 90, 200), 0.7));
}

TEST(TrackerPasses, ALookFoundWhereItAlreadyWasHasNotAppeared) {
  cv::Mat before(200, 200, CV_8UC1);
  cv::RNG background(11);
  background.fill(before, cv::RNG::UNIFORM, 0, 256);
  cv::Mat look(21, 21, CV_8UC1);
  cv::RNG texture(5);
  texture.fill(look, cv::RNG::UNIFORM, 90, 170);
  look.copyTo(before(cv::Rect(40, 40, 21, 21)));   // the hand, detected here
  look.copyTo(before(cv::Rect(140, 40, 21, 21)));  // clutter that looks like it
  PatchFollower follower;
  follower.remember(before, {50, 50}, 21);
  ASSERT_FALSE(follower.empty());
  EXPECT_FALSE(appearedSince(follower, before, {150, 50}, 5, 0.7));  // the clutter
  EXPECT_FALSE(appearedSince(follower, before, {153, 47}, 5, 0.7));  // ... a little moved
  EXPECT_TRUE(appearedSince(follower, before, {150, 150}, 5, 0.7));  // the background
  EXPECT_TRUE(appearedSince(follower, cv::Mat(), {150, 50}, 5, 0.7));
}

TEST(TrackerPasses, OnlyMissedTracksAreFollowedByTheirLook) {
  std::array<HandTrack, 2> hands = {handAt({420, 380}, 0.0), handAt({220, 380}, 0.0)};
  const std::vector<HandDetection> none;
  HandFrame f = handFrame(none);
  f.steps[1].updated = true;
  std::vector<int> tried;
  followBlindWhereMissed(hands, f, [&](int k) {
    tried.push_back(k);
    return true;
  });
  EXPECT_EQ(tried, std::vector<int>{0});
  EXPECT_TRUE(f.steps[0].updated && f.steps[0].followedBlind);
  EXPECT_FALSE(f.steps[1].followedBlind);

  hands[0].track.reset();
  HandFrame g = handFrame(none);
  tried.clear();
  followBlindWhereMissed(hands, g, [&](int k) {
    tried.push_back(k);
    return false;
  });
  EXPECT_EQ(tried, std::vector<int>{1});
  EXPECT_FALSE(g.steps[1].updated || g.steps[1].followedBlind);
}

TEST(TrackerPasses, ATrackOnASpeckMovesToTheNearestFreeSolidCandidate) {
  TrackerOptions o;
  const std::vector<HandDetection> dets = {cand({420, 380}, 5, 1), cand({600, 380}),
                                           cand({480, 380}), cand({200, 380})};
  {
    std::array<HandTrack, 2> hands = {handAt({420, 380}, 0.0), HandTrack{}};
    HandFrame f = handFrame(dets);
    f.steps[0] = {true, false, std::size_t{0}, &dets[0]};
    f.taken[0] = true;
    moveToSolidCandidates(hands, f, o);
    EXPECT_EQ(f.steps[0].held, std::optional<std::size_t>(2));  // not 3: the other side
    EXPECT_EQ(f.steps[0].detectedBy, &dets[2]);
    EXPECT_TRUE(same(hands[0].track->position(), {480, 380}));
    EXPECT_EQ(hands[0].track->lastUpdateS(), f.t);  // restarted there
    EXPECT_EQ(f.taken, (std::vector<bool>{false, false, true, false}));
  }
  {  // held by a solid candidate, or followed by its look: stays
    std::array<HandTrack, 2> hands = {handAt({480, 380}, 0.0), handAt({220, 380}, 0.0)};
    HandFrame f = handFrame(dets);
    f.steps[0] = {true, false, std::size_t{2}, &dets[2]};
    f.steps[1] = {true, true, std::nullopt, nullptr};
    f.taken[2] = true;
    moveToSolidCandidates(hands, f, o);
    EXPECT_EQ(f.steps[0].held, std::optional<std::size_t>(2));
    EXPECT_FALSE(f.steps[1].held);
    EXPECT_EQ(f.taken, (std::vector<bool>{false, false, true, false}));
  }
  {  // followed by a look found in a search of the band: a solid candidate wins
    std::array<HandTrack, 2> hands = {HandTrack{}, handAt({60, 380}, 0.0)};
    HandFrame f = handFrame(dets);
    f.steps[1] = {true, true, std::nullopt, nullptr, true};
    moveToSolidCandidates(hands, f, o);
    EXPECT_EQ(f.steps[1].held, std::optional<std::size_t>(3));
    EXPECT_FALSE(f.steps[1].followedBlind || f.steps[1].lookYields);
    EXPECT_TRUE(same(hands[1].track->position(), {200, 380}));
  }
  {  // a missed track moves too, unless solidHandAreaFaces is 0
    std::array<HandTrack, 2> hands = {HandTrack{}, handAt({250, 380}, 0.0)};
    HandFrame f = handFrame(dets);
    o.solidHandAreaFaces = 0;
    moveToSolidCandidates(hands, f, o);
    EXPECT_FALSE(f.steps[1].updated);
    o.solidHandAreaFaces = 0.12;
    moveToSolidCandidates(hands, f, o);
    EXPECT_EQ(f.steps[1].held, std::optional<std::size_t>(3));
  }
}

TEST(TrackerPasses, AMissedHandIsReacquiredOnlyNearWhereItWasLastSeen) {
  const TrackerOptions o;  // reacquireFaceWidths 1.5: 90 px
  const cv::Point2f seen(420, 380);
  const auto missed = [&] {
    HandTrack h = handAt({470, 300}, 0.0);  // the track went elsewhere
    h.lastSeen = seen;
    return std::array<HandTrack, 2>{h, HandTrack{}};
  };
  {
    auto hands = missed();
    const std::vector<HandDetection> far = {cand({seen.x + 91, seen.y})};
    HandFrame f = handFrame(far);
    reacquireNearLastSeen(hands, f, o);
    EXPECT_FALSE(f.steps[0].updated);
  }
  {
    auto hands = missed();
    const std::vector<HandDetection> near = {cand({seen.x + 89, seen.y})};
    HandFrame f = handFrame(near);
    reacquireNearLastSeen(hands, f, o);
    EXPECT_TRUE(f.steps[0].updated);
    EXPECT_TRUE(same(hands[0].track->position(), near[0].centroid));
    EXPECT_TRUE(same(hands[0].lastSeen, near[0].centroid));
  }
  {  // of equally near candidates the last is taken; taken ones are skipped
    auto hands = missed();
    const std::vector<HandDetection> equal = {
        cand({seen.x + 50, seen.y}), cand({seen.x, seen.y + 50}), cand({seen.x + 30, seen.y + 40})};
    HandFrame f = handFrame(equal);
    reacquireNearLastSeen(hands, f, o);
    EXPECT_EQ(f.steps[0].detectedBy, &equal[2]);
    auto again = missed();
    HandFrame g = handFrame(equal);
    g.taken[2] = true;
    reacquireNearLastSeen(again, g, o);
    EXPECT_EQ(g.steps[0].detectedBy, &equal[1]);
  }
  {  // an updated hand is left alone
    auto hands = missed();
    const std::vector<HandDetection> near = {cand({seen.x + 10, seen.y})};
    HandFrame f = handFrame(near);
    f.steps[0].updated = true;
    reacquireNearLastSeen(hands, f, o);
    EXPECT_FALSE(f.taken[0]);
  }
}

TEST(TrackerPasses, ACoastingHandJumpsOnlyAfterCoastJumpS) {
  TrackerOptions o;  // coastJumpS 0.1
  const std::vector<HandDetection> dets = {cand({200, 380}), cand({700, 380}), cand({600, 380})};
  {
    std::array<HandTrack, 2> hands = {handAt({420, 380}, 0.0), HandTrack{}};
    HandFrame f = handFrame(dets, 0.05);
    jumpAfterCoasting(hands, f, o);
    EXPECT_FALSE(f.steps[0].updated);
  }
  {
    std::array<HandTrack, 2> hands = {handAt({420, 380}, 0.0), HandTrack{}};
    HandFrame f = handFrame(dets, 0.2);
    jumpAfterCoasting(hands, f, o);
    EXPECT_EQ(f.steps[0].detectedBy, &dets[2]);  // nearest on its side, however far
    EXPECT_TRUE(same(hands[0].track->position(), {600, 380}));
  }
  {
    o.coastJumpS = 0;  // never
    std::array<HandTrack, 2> hands = {handAt({420, 380}, 0.0), HandTrack{}};
    HandFrame f = handFrame(dets, 0.2);
    jumpAfterCoasting(hands, f, o);
    EXPECT_FALSE(f.steps[0].updated);
  }
}

TEST(TrackerPasses, AMissedHandCoastsSlowerAndIsDroppedAfterCoastS) {
  const TrackerOptions o;  // coastVelocityDamping 0.5, coastS 0.4
  std::array<HandTrack, 2> hands = {handAt({420, 380}, 0.0), handAt({220, 380}, 0.0)};
  for (HandTrack& h : hands) {
    h.track->predict(0.1);
    h.track->update(h.track->position() + cv::Point2f(10, 0));
  }
  const cv::Point2f v0 = hands[0].track->velocity();
  const cv::Point2f v1 = hands[1].track->velocity();
  ASSERT_GT(v0.x, 0);
  const std::vector<HandDetection> none;
  HandFrame f = handFrame(none, 0.3);
  f.steps[1].updated = true;
  coastOrDrop(hands, f, o);
  EXPECT_FLOAT_EQ(hands[0].track->velocity().x, 0.5f * v0.x);
  EXPECT_FLOAT_EQ(hands[1].track->velocity().x, v1.x);  // updated: untouched
  f.t = 0.45;                                           // 0.35 s after the last update
  coastOrDrop(hands, f, o);
  EXPECT_TRUE(hands[0].track);
  f.t = 0.6;
  coastOrDrop(hands, f, o);
  EXPECT_FALSE(hands[0].track);
  EXPECT_TRUE(hands[1].track);
}

TEST(TrackerPasses, NewHandsStartNearestTheirRestPlaceOnTheirOwnSide) {
  const TrackerOptions o;
  EXPECT_TRUE(same(restPlace(0, kHead, kFw), {404, 378}));
  EXPECT_TRUE(same(restPlace(1, kHead, kFw), {236, 378}));
  const std::vector<HandDetection> dets = {cand({330, 378}), cand({410, 380}), cand({236, 378}),
                                           cand({310, 378})};
  std::array<HandTrack, 2> hands;
  HandFrame f = handFrame(dets);
  f.taken[2] = true;
  startNewHands(hands, f, o);
  EXPECT_EQ(f.steps[0].detectedBy, &dets[1]);
  EXPECT_EQ(f.steps[1].detectedBy, &dets[3]);
  EXPECT_TRUE(same(hands[0].track->position(), {410, 380}));
  EXPECT_TRUE(same(hands[1].lastSeen, {310, 378}));
  EXPECT_EQ(f.taken, (std::vector<bool>{false, true, true, true}));

  // Only the head's own side, not crossFaceWidths across it; tracked hands
  // do not restart.
  const std::vector<HandDetection> across = {cand({325, 378})};
  std::array<HandTrack, 2> one = {handAt({420, 380}, 0.0), HandTrack{}};
  HandFrame g = handFrame(across);
  startNewHands(one, g, o);
  EXPECT_FALSE(one[1].track);
  EXPECT_FALSE(g.taken[0]);
  EXPECT_TRUE(same(one[0].track->position(), {420, 380}));
}

// ---- the report ------------------------------------------------------------------

TEST(TrackerPasses, TheReportFillsTheBodyOnlyForTheGodfather) {
  const TrackerOptions o;
  SubjectTracks s;
  s.head.emplace(kHead, 1.0, o.head);
  s.faceWidth = 60;
  s.hands[0] = handAt({420, 380}, 0.5);
  s.hands[1] = handAt({220, 380}, 1.0);
  StereoFrame frame;
  frame.index = 30;
  BodySample body;
  TrackingState st = reportState(frame, 1.0, ElectionState::Godfather, 2.5, s, o.rig, body);
  EXPECT_EQ(st.timeS, 1.0);
  EXPECT_EQ(st.candidateS, 2.5);
  EXPECT_EQ(st.faceWidthPx, 60);
  EXPECT_TRUE(st.head.observed);
  EXPECT_TRUE(st.leftHand.tracked);
  EXPECT_FALSE(st.leftHand.observed);  // last updated at 0.5
  EXPECT_TRUE(st.rightHand.observed);
  ASSERT_TRUE(st.triangle);
  EXPECT_TRUE(body.godfather);
  EXPECT_EQ(body.frame, 30);
  EXPECT_TRUE(same(body.leftHand.image, {420, 380}));

  st = reportState(frame, 1.0, ElectionState::Candidate, 0.5, s, o.rig, body);
  EXPECT_TRUE(st.head.tracked);
  EXPECT_FALSE(body.godfather);
  EXPECT_FALSE(body.head.tracked);

  s.head.reset();
  s.hands[1].track.reset();
  st = reportState(frame, 1.0, ElectionState::Godfather, 0, s, o.rig, body);
  EXPECT_EQ(st.faceWidthPx, 0);
  EXPECT_FALSE(st.triangle);
  EXPECT_FALSE(body.godfather);
}

}  // namespace
}  // namespace horopter::detail
