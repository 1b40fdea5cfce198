// The tracking stage: the godfather election over the detected faces, then
// the godfather's head and both hands tracked by constant-velocity Kalman
// filters with gating. Fills Frame::tracking and Frame::body (the contract
// with movement analysis, horopter/interaction/body.hpp).
#pragma once

#include "horopter/core/export.hpp"

#include <span>

#include "horopter/core/option_table.hpp"

#include <functional>
#include <memory>
#include <optional>

#include "horopter/hardware/head.hpp"
#include "horopter/interaction/body.hpp"
#include "horopter/interaction/detection.hpp"
#include "horopter/interaction/godfather.hpp"
#include "horopter/interaction/kalman_track.hpp"
#include "horopter/vision/geometry.hpp"
#include "horopter/vision/stereo_frame.hpp"

namespace horopter {

// The pose the frame was captured with (synthetic: its truth; a real head:
// its measurement at capture); std::nullopt where unknown.
using CapturePose = std::function<std::optional<hw::HeadAngles>(const StereoFrame&)>;

struct HOROPTER_API TrackerOptions {
  ElectionOptions election;
  KalmanOptions head{800, 3, 200, 13.8, 12};
  // Hands start and stop within a frame or two (a wave's turn): a large
  // acceleration noise keeps them in the gate.
  KalmanOptions hands{30000, 4, 600, 13.8, 15};
  // A hand that left its gate is taken up again at the free candidate within
  // this many face widths of where it was last seen.
  double reacquireFaceWidths = 1.5;
  // However wide the Kalman gate grows, a detection further than this many
  // face widths from a hand's prediction is not that hand.
  double maxHandStepFaceWidths = 2.0;
  // A coasting track's velocity is multiplied by this each frame without a
  // detection.
  double coastVelocityDamping = 0.5;
  double coastS = 0.4;  // a track without detections is dropped after this long
  // A hand track without detections for longer than this moves to the free
  // candidate on its side nearest to it (0: never; it waits to be dropped).
  double coastJumpS = 0.1;
  // A hand candidate must lie within this many face widths of the head, and
  // its area be between these many squared face widths (a hand is about
  // 0.27; larger: merged with clutter, smaller: a speck or a hand's edge).
  double reachFaceWidths = 7;
  double minHandAreaFaces = 0.02;
  double maxHandAreaFaces = 1.0;
  // ... and the largest disc inside it at least this many face widths in
  // radius (a hand's is about 0.2 once opened; slivers of wall let in by the
  // fattened silhouette are a few pixels thick).
  double minHandRadiusFaces = 0.05;
  // ... and, where measured (the region), most of its pixels agreeing
  // between the views at their disparity (HandDetection::stereoAgreement).
  double minStereoAgreement = 0.7;
  // A small candidate (under smallHandAreaFaces squared face widths or
  // smallHandRadiusFaces of radius: a hand partly outside the zone, or a
  // speck) needs this much agreement: the hand's pixels agree, a speck of
  // wall that block matching pulled forward mostly does not.
  double smallHandAreaFaces = 0.05;
  double smallHandRadiusFaces = 0.09;
  double smallHandMinAgreement = 0.9;
  // ... and, once the subject's face skin luma is known, a mean grey level
  // of at least this fraction of it (0: no limit). Cloth whose chroma is
  // skin's is far darker than skin under the same light: on tuning seed
  // 10053 (a brown shirt) the hands' candidates measured 0.6-1.5 of the
  // face's luma, the shirt's pieces 0.28-0.54 (90 % under 0.54).
  double minHandLumaOfFace = 0.55;
  // A solid hand candidate: at least this area (squared face widths) and
  // inscribed radius (face widths). A track on a weaker candidate, or on
  // none, moves to a free solid one on its side (0: never).
  double solidHandAreaFaces = 0.12;
  double solidHandRadiusFaces = 0.15;
  // When the cascade misses the face, the head's track follows the largest
  // round skin blob (at least 0.3 squared face widths, radius 0.2) within
  // this many face widths of its prediction (0: it coasts).
  double headBlobFaceWidths = 0.5;
  // Where stereo is blind, no zone and so no candidate can hold a hand,
  // though the left image shows it: left of x = d + blindBandFaces face
  // widths (d: the hand's last disparity; the right camera does not see
  // there), or with d above blindNearFraction of maxDisparityPx (the hand
  // is leaving the search range towards the cameras), where under
  // blindValidFraction of the disparities within a third of a face width of
  // the prediction are valid. A hand track missed there follows the hand's last detected look (a
  // grey patch blindPatchFaces face widths across) within blindSearchFaces face widths of its
  // prediction or where it was last seen, where it correlates by at least blindMinScore, for at
  // most blindFollowS after the last detection (0: off).
  double blindFollowS = 1.0;
  double blindBandFaces = 0.5;
  double blindNearFraction = 0.85;
  double blindValidFraction = 0.5;
  double blindPatchFaces = 0.3;
  double blindSearchFaces = 0.5;
  double blindMinScore = 0.7;
  // A missed hand whose track or last sighting is within this many face
  // widths right of the band the right view does not see (x < d +
  // blindBandFaces face widths) is also looked for by its look anywhere in
  // the band near its rows (0: off): a pointing arm reaches the band faster
  // than its track follows. A find counts only where it is like the look in
  // level and contrast and was not there in the image of the last detection
  // (skin-coloured clutter is), and a track so followed gives way to a solid
  // candidate on its side.
  double bandSearchFaces = 3.0;
  // 1: a missed hand is also blind where the front end found no disparity
  // around its prediction for another cause (no texture: a smooth hand in
  // dim light or noise), not only out of the right view or too near. Off:
  // on tuning seeds 10272-10311 it turned 41 no-disparity part-frames into
  // 63 "elsewhere" ones (false looks), 6.29 -> 6.40 % region loss.
  double blindTextureless = 0;
  // The front end's largest disparity, px (0: unknown, no near blindness).
  double maxDisparityPx = 0;
  // A candidate whose mean disparity is at least this fraction of
  // maxDisparityPx is no hand (0: no limit). Skin-coloured wood behind a
  // person's shoulder, matched against the end of the search range (93 of
  // 95 px), held the right hand's track for whole trials (tuning seeds
  // 10003, 10004, 10042: 302 such candidates at 90 px or more, none of the
  // hands'); a hand that near is blind to the front end anyway and
  // followed by its look.
  double pinnedDisparityFraction = 0.94;
  // ... but a hand track whose hand was last measured at this fraction of
  // maxDisparityPx or more (brought towards the cameras) may take a solid
  // pinned candidate near it (0: never). On tuning seeds 10352-10391, 53 of
  // 87 right-hand "elsewhere" frames had the whole hand at 89-95 px,
  // refused as pinned; the wood stays refused to tracks not measured near.
  double pinnedNearFraction = 0.85;
  // A hand's track takes no candidate further than this many face widths
  // across the head's vertical to the other hand's side (a circle or a
  // wave crosses the midline by about half a face width).
  double crossFaceWidths = 0.6;
  // The frame's time: index / framesPerSecond (deterministic, for recorded
  // and synthetic input) or, with captureTime, the capture timestamps.
  double framesPerSecond = 30;
  bool captureTime = false;
  // The rectified rig, for 3-D positions from Frame::disparity (focalPx 0:
  // no 3-D, rig coordinates stay NaN).
  RectifiedGeometry rig;
  // The head's pose at capture. Where given (with the rig), the tracks move
  // with the image when the head turns between frames, so a turn is not
  // mistaken for the parts' own motion; empty: tracks stay where they were.
  CapturePose capturePose;
};

// The tracker's options a user tunes (flags, help, ranges, JSON keys); validation
// checks them against it.
HOROPTER_API std::span<const NumberOption<TrackerOptions>> trackerOptions();

struct HOROPTER_API TrackingState {
  double timeS = 0;
  ElectionState election = ElectionState::None;
  double candidateS = 0;  // how long the candidate has been inside
  float faceWidthPx = 0;  // the subject's last face width
  // The subject's tracks (candidate or godfather); Frame::body holds them
  // only once the godfather is elected.
  PartState head, leftHand, rightHand;
  std::optional<BodyTriangle> triangle;  // from the godfather's tracked parts
  // Filled by the head-control stage: the pan/tilt command issued from this
  // frame, and the frame it takes effect at.
  std::optional<hw::HeadAngles> headCommand;
  std::int64_t headCommandFrame = -1;
};

// The tracker's state machine, one frame at a time (in order).
class HOROPTER_API BodyTracker {
 public:
  explicit BodyTracker(TrackerOptions options);  // throws horopter::Error for bad options
  ~BodyTracker();
  BodyTracker(BodyTracker&&) noexcept;
  // The frame's detections in, the state out; fills `body`.
  TrackingState update(const StereoFrame& frame, const Detections& detections, BodySample& body);
  const TrackerOptions& options() const { return options_; }

 private:
  // Moves the tracks with the image when the head turned since the last frame.
  void followHeadTurn(const StereoFrame& frame);
  // Hand k, missed where stereo is blind, follows its look (true: found).
  bool followBlind(int k, const StereoFrame& frame, cv::Point2f head, double fw, double t);
  // Keeps the look of hand k detected as `detected` this frame (or none).
  void rememberLook(int k, const HandDetection* detected, const StereoFrame& frame, double fw,
                    double t);
  struct Impl;
  TrackerOptions options_;
  std::unique_ptr<Impl> impl_;
};

// The rig-frame point (metres) seen at `pixel` of the left image, from the
// median valid disparity of Frame::disparity within `window` around it; NaN
// when no valid disparity is there.
HOROPTER_API cv::Point3f rigPointFromDisparity(const cv::Mat& disparity,
                                               const RectifiedGeometry& rig, cv::Point2f pixel,
                                               cv::Rect window);

}  // namespace horopter
