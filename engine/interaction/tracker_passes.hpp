// The passes BodyTracker::update runs each frame, as free functions on plain
// data (the subject's tracks, this frame's hand candidates and which of them
// are taken) so each can be tested alone. Internal to engine/interaction; see
// horopter/interaction/tracking.hpp for the options they read.
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

#include "horopter/interaction/detection.hpp"
#include "horopter/interaction/godfather.hpp"
#include "horopter/interaction/kalman_track.hpp"
#include "horopter/interaction/tracking.hpp"
#include "horopter/vision/stereo_frame.hpp"

namespace horopter::detail {

// ---- the data the passes work on ----------------------------------------

// One hand's track and where it was last observed.
struct HandTrack {
  std::optional<ConstantVelocityTrack> track;
  cv::Point2f lastSeen;
};

// The subject's tracks: head and hands, [0] the person's left, [1] right.
struct SubjectTracks {
  std::optional<ConstantVelocityTrack> head;
  float faceWidth = 0;  // the subject's last face width, px
  float faceLuma = 0;   // the skin's grey level in the subject's last face (0: unknown)
  std::array<HandTrack, 2> hands;
};

// The start of the capture-time clock (TrackerOptions::captureTime).
struct FrameClock {
  bool haveStart = false;
  SteadyClock::time_point start{};
};

// What became of one hand in this frame, pass by pass.
struct HandStep {
  bool updated = false;        // a candidate or its look moved the track this frame
  bool followedBlind = false;  // ... its look, where stereo is blind
  // The candidate the track holds after gated assignment or the move to a
  // solid candidate (nothing: none).
  std::optional<std::size_t> held;
  const HandDetection* detectedBy = nullptr;  // this frame's candidate, if any
  // Followed by a look that was found by a search of the band (this frame or since the last
  // detection): it gives way to a solid candidate.
  bool lookYields = false;
};

// What the hand passes share in one frame.
struct HandFrame {
  cv::Point2f head;                              // the head track's position
  double fw = 1;                                 // the face width, px (at least 1)
  double t = 0;                                  // the frame's time, s
  std::vector<const HandDetection*> candidates;  // the plausible hand candidates
  std::vector<bool> taken;                       // per candidate: a track holds it
  // Refused only for their disparity pinned at the range's end (takePinnedNearHands).
  std::vector<const HandDetection*> pinned;
  std::array<HandStep, 2> steps;  // per hand
};

// ---- helpers ------------------------------------------------------------

// +1 for the person's left hand (k 0), which appears on the image's right;
// -1 for the right hand.
inline double sideSign(int k) {
  return k == 0 ? 1.0 : -1.0;
}

// Whether a candidate at `c` may be hand k: not further than crossFaceWidths
// face widths across the head's vertical to the other hand's side.
bool onHandSide(int k, cv::Point2f c, cv::Point2f head, double fw, const TrackerOptions& o);

// How equal distances are decided in nearestFreeCandidate.
enum class Ties { LowestIndex, HighestIndex };

// The candidate nearest `from` that is not taken and is `eligible`, within
// `maxDistance` (inclusive) where given; nothing where none is. Equal
// distances go to the lowest index, or with Ties::HighestIndex the highest.
std::optional<std::size_t> nearestFreeCandidate(const std::vector<const HandDetection*>& candidates,
                                                const std::vector<bool>& taken,
                                                const std::function<bool(std::size_t)>& eligible,
                                                cv::Point2f from,
                                                std::optional<double> maxDistance = std::nullopt,
                                                Ties ties = Ties::LowestIndex);

// Hand k takes candidate j of `f`: the track restarts there (`restart`) or is
// updated with it; it is where the hand was last seen, is taken, and is this
// frame's detection of the hand.
void takeCandidate(HandTrack& hand, HandFrame& f, int k, std::size_t j, bool restart,
                   const TrackerOptions& o);

// ---- the passes, in the order update runs them ---------------------------

// The frame's time: index / framesPerSecond, or with captureTime the
// capture timestamp since the first frame's.
double frameTimeS(const StereoFrame& frame, const TrackerOptions& o, FrameClock& clock);

// Every track is predicted to time t.
void predictTracks(SubjectTracks& s, double t);

// The gated face nearest the head's prediction (first of equals), if any.
const FaceDetection* nearestFaceInGate(const ConstantVelocityTrack& head,
                                       const std::vector<FaceDetection>& faces);
// The largest round skin blob (at least 0.3 squared face widths, radius 0.2)
// within headBlobFaceWidths face widths of the head's prediction, if any
// (first of equals).
const HandDetection* headSkinBlob(const ConstantVelocityTrack& head, float faceWidth,
                                  const std::vector<HandDetection>& blobs, const TrackerOptions& o);
// The largest face inside the zone, if any (first of equals).
const FaceDetection* largestFaceInside(const std::vector<FaceDetection>& faces);

// The subject's face: the gated detection nearest the head track, its skin
// blob where the cascade missed it, or a new subject (the largest face
// inside the zone) when there is no track. Returns whether the subject was
// seen inside the zone (nothing: not seen).
std::optional<bool> associateHead(SubjectTracks& s, const Detections& det, double t,
                                  const TrackerOptions& o);

// The election's step; a head that coasted past coastS is dropped, and
// without an elected subject or a head every track is.
ElectionState updateElection(GodfatherElection& election, SubjectTracks& s,
                             std::optional<bool> seenInside, double t, const TrackerOptions& o);

// Whether a candidate at `c` is the face or neck itself (the detector cuts
// them out only around the faces it finds).
bool faceOrNeck(cv::Point2f c, cv::Point2f head, double fw);
// The candidates that may be hands: not the face or neck, within reach, of
// a hand's area and radius, agreeing between the views, and, where the
// face's skin luma is known, not much darker than it (minHandLumaOfFace);
// and not pinned at the range's end (pinnedDisparityFraction): those that
// pass every other test go to `pinnedOut`, where given.
std::vector<const HandDetection*> plausibleHandCandidates(
    const std::vector<HandDetection>& hands, cv::Point2f head, double fw, const TrackerOptions& o,
    float faceLuma = 0, std::vector<const HandDetection*>* pinnedOut = nullptr);
// This frame's hand context: the plausible candidates, none taken, and the pinned ones.
HandFrame startHandFrame(const ConstantVelocityTrack& head, float faceWidth, const Detections& det,
                         double t, const TrackerOptions& o, float faceLuma = 0);

// Gated nearest-first assignment of the candidates to the existing tracks:
// one candidate per track and one track per candidate.
void assignGated(std::array<HandTrack, 2>& hands, HandFrame& f, const TrackerOptions& o);

// A missed track whose hand was last measured near (its disparity
// `handDisparity[k]`, px, at least pinnedNearFraction of maxDisparityPx)
// takes the nearest solid pinned candidate on its side within its gate and
// step limit or within reacquireFaceWidths of where it was last seen; the
// candidate joins the frame's candidates, taken.
void takePinnedNearHands(std::array<HandTrack, 2>& hands, HandFrame& f,
                         const std::array<double, 2>& handDisparity, const TrackerOptions& o);

// Whether stereo is blind at a missed hand's prediction: the front end
// found under blindValidFraction valid disparities there (`validFraction`),
// and the hand is left of what the right view sees or nearer than the range
// by its last disparity (`handDisparity`, 0: unknown), or, with
// blindTextureless, for any cause (a smooth hand in dim light).
bool stereoBlindAt(cv::Point2f predicted, double handDisparity, double validFraction, double fw,
                   const TrackerOptions& o);

// Where a missed hand may have gone out of the right view: a pointing arm
// stretched out to the person's right reaches the band on the image's left
// in a few frames, too far from its coasting track for the look's search
// around it. The centres left of x = d + blindBandFaces face widths (d: the
// hand's last disparity; the right camera does not see there, so no
// candidate can hold the hand, and stereo's silence is certain, not a
// texture doubt), within a face width of the rows between its prediction
// and where it was last seen, clipped to `image`. Nothing where the band
// search is off (bandSearchFaces 0), d is unknown, or both the prediction
// and the last sighting lie more than bandSearchFaces face widths right of
// the band.
std::optional<cv::Rect> rightViewBandWindow(cv::Point2f predicted, cv::Point2f lastSeen,
                                            double handDisparity, double fw, cv::Size image,
                                            const TrackerOptions& o);

// Each tracked hand missed so far is tried with `follow(k)` (its look, where
// stereo is blind).
void followBlindWhereMissed(const std::array<HandTrack, 2>& hands, HandFrame& f,
                            const std::function<bool(int)>& follow);

// Whether candidate j is solid (a whole hand, not a speck).
bool solidCandidate(const HandFrame& f, std::size_t j, const TrackerOptions& o);
// A track held by a weak candidate, or by none, or by a look that yields,
// moves to the nearest free solid candidate on its side.
void moveToSolidCandidates(std::array<HandTrack, 2>& hands, HandFrame& f, const TrackerOptions& o);

// A missed track is taken up again at the free candidate nearest where it
// was last seen, within reacquireFaceWidths.
void reacquireNearLastSeen(std::array<HandTrack, 2>& hands, HandFrame& f, const TrackerOptions& o);

// A track missed for longer than coastJumpS moves to the free candidate on
// its side nearest to it.
void jumpAfterCoasting(std::array<HandTrack, 2>& hands, HandFrame& f, const TrackerOptions& o);

// A missed track coasts (its velocity damped), and is dropped once missed
// for longer than coastS.
void coastOrDrop(std::array<HandTrack, 2>& hands, const HandFrame& f, const TrackerOptions& o);

// Where hand k rests: beside and below the head, on its own side.
cv::Point2f restPlace(int k, cv::Point2f head, double fw);
// A hand without a track starts at the free candidate on its own side of
// the head nearest its resting place.
void startNewHands(std::array<HandTrack, 2>& hands, HandFrame& f, const TrackerOptions& o);

// One part's state from its track (observed: updated at timeS), with its
// rig point from the disparity within `windowPx` around it.
PartState partOf(const std::optional<ConstantVelocityTrack>& track, double timeS,
                 const StereoFrame& frame, const RectifiedGeometry& rig, int windowPx);

// The frame's state and body sample from the tracks.
TrackingState reportState(const StereoFrame& frame, double t, ElectionState state,
                          double candidateS, const SubjectTracks& s, const RectifiedGeometry& rig,
                          BodySample& body);

}  // namespace horopter::detail
