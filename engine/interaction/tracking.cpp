// The godfather's election and Kalman tracks of head and hands; see
// horopter/interaction/tracking.hpp.
#include "horopter/interaction/tracking.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "blind_follow.hpp"
#include "horopter/core/error.hpp"
#include "horopter/interaction/head_control.hpp"
#include "tracker_passes.hpp"

namespace horopter {

cv::Point3f rigPointFromDisparity(const cv::Mat& disparity, const RectifiedGeometry& rig,
                                  cv::Point2f pixel, cv::Rect window) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  if (disparity.empty() || disparity.type() != CV_16SC1 || !(rig.focalPx > 0) ||
      !(rig.baseline > 0))
    return {nan, nan, nan};
  window &= cv::Rect(0, 0, disparity.cols, disparity.rows);
  std::vector<std::int16_t> valid;
  valid.reserve(static_cast<std::size_t>(std::max(0, window.area())));
  for (int y = window.y; y < window.y + window.height; ++y) {
    const auto* row = disparity.ptr<std::int16_t>(y);
    for (int x = window.x; x < window.x + window.width; ++x)
      if (row[x] > 0) valid.push_back(row[x]);
  }
  if (valid.empty()) return {nan, nan, nan};
  auto middle = valid.begin() + static_cast<std::ptrdiff_t>(valid.size() / 2);
  std::nth_element(valid.begin(), middle, valid.end());
  const double d = *middle / 16.0;
  const double z = rig.focalPx * rig.baseline / d;
  // The rig's origin is midway between the cameras; the left one is at -B/2.
  return {static_cast<float>((pixel.x - rig.cx) * z / rig.focalPx - 0.5 * rig.baseline),
          static_cast<float>((pixel.y - rig.cy) * z / rig.focalPx), static_cast<float>(z)};
}

struct BodyTracker::Impl {
  explicit Impl(const TrackerOptions& o) : election(o.election) {}
  GodfatherElection election;
  detail::SubjectTracks subject;   // head and hands, with where each hand was last seen
  detail::PatchFollower looks[2];  // each hand's last detected patch, for where stereo is blind
  double lastDetectedS[2] = {0, 0};
  double handDisparity[2] = {0, 0};        // px, where last detected (0: unknown)
  bool bandLook[2] = {false, false};       // followed since a band search found its look
  cv::Mat detectedGrey[2];                 // the left grey image of each look's detection
  cv::Mat greyCopy;                        // this update's copy, shared by both hands
  std::uint64_t updates = 0;               // calls of update(), to know the copy's
  std::uint64_t greyCopyUpdate = 0;        // the update it was copied in (0: none)
  std::optional<hw::HeadAngles> lastPose;  // the previous frame's, with capturePose
  double headDepthM = 0;                   // the head's last measured depth (0: none yet)
  detail::FrameClock clock;
};

namespace {

// How far from a band search's find the look is sought in the image of
// its last detection (face widths): a small head turn moves clutter that far.
constexpr double kAppearedRadiusFaces = 0.25;

// The depth a turn is undone at before the head's depth is measured.
constexpr double kUnknownDepthM = 1.5;

// The table's options (the ones a user tunes) are checked by their ranges;
// the rest are internal gates, checked here, and not exposed as flags.
void validate(const TrackerOptions& o) {
  checkRanges(trackerOptions(), o);
  if (!(o.coastS >= 0) || !(o.reachFaceWidths > 0) || !(o.maxHandAreaFaces > o.minHandAreaFaces) ||
      o.minHandAreaFaces < 0)
    throw Error("tracker coast time must be >= 0 s, reach and hand area > 0");
  if (!(o.minHandRadiusFaces >= 0) || !(o.crossFaceWidths >= 0) || !(o.solidHandAreaFaces >= 0) ||
      !(o.solidHandRadiusFaces >= 0) || !(o.headBlobFaceWidths >= 0))
    throw Error(
        "tracker hand radius, crossing, solid-hand and head-blob limits must be >= 0 face widths");
  if (!(o.minStereoAgreement >= 0 && o.minStereoAgreement <= 1) ||
      !(o.smallHandMinAgreement >= 0 && o.smallHandMinAgreement <= 1) ||
      !(o.smallHandAreaFaces >= 0) || !(o.smallHandRadiusFaces >= 0))
    throw Error("tracker stereo agreements must be fractions in [0, 1] and small-hand limits >= 0");
  if (!(o.blindBandFaces >= 0) || !(o.blindNearFraction > 0) ||
      !(o.blindValidFraction >= 0 && o.blindValidFraction <= 1) || !(o.blindPatchFaces > 0) ||
      !(o.blindSearchFaces > 0) || !(o.maxDisparityPx >= 0))
    throw Error(
        "tracker blind following needs a band and largest disparity >= 0, a near fraction, "
        "patch and search sizes > 0 and a valid fraction in [0, 1]");
  if (!(o.framesPerSecond > 0) || !std::isfinite(o.framesPerSecond))
    throw Error("tracker framesPerSecond must be positive");
}

}  // namespace

std::span<const NumberOption<TrackerOptions>> trackerOptions() {
  using O = TrackerOptions;
  static const NumberOption<O> table[] = {
      {"coastJumpS", "--coast-jump-s", "s", 0, 60,
       "a hand track without detections for this long moves to the free hand candidate",
       &O::coastJumpS},
      {"pinnedDisparityFraction", "--pinned-disparity", "", 0, 1,
       "a hand candidate whose disparity is at least this fraction of the largest searched is "
       "refused (0: no limit)",
       &O::pinnedDisparityFraction},
      {"pinnedNearFraction", "--pinned-near-hand", "", 0, 1,
       "... but a hand last measured at this fraction of the largest disparity or more may take "
       "a solid pinned candidate near it (0: never)",
       &O::pinnedNearFraction},
      {"minHandLumaOfFace", "--min-hand-luma", "", 0, 4,
       "a hand candidate's mean grey level must be at least this fraction of the face's (0: off)",
       &O::minHandLumaOfFace},
      {"blindFollowS", "--blind-follow-s", "s", 0, 60,
       "where stereo is blind, a missed hand follows its look for at most this long after its "
       "last detection (0: off)",
       &O::blindFollowS},
      {"blindMinScore", "--blind-min-score", "", -1, 1,
       "... where the look correlates by at least this", &O::blindMinScore},
      {"bandSearchFaces", "--band-search-faces", "face widths", 0, 20,
       "a missed hand within this distance of the band the right view does not see is looked "
       "for by its look anywhere in the band (0: off)",
       &O::bandSearchFaces},
      {"blindTextureless", "--blind-textureless", "", 0, 1,
       "1: a missed hand is blind wherever the front end found no disparity around it, not "
       "only out of the right view or nearer than the range (measured worse: off)",
       &O::blindTextureless},
  };
  return table;
}

BodyTracker::BodyTracker(TrackerOptions options) : options_(options) {
  validate(options_);
  impl_ = std::make_unique<Impl>(options_);
}
BodyTracker::~BodyTracker() = default;
BodyTracker::BodyTracker(BodyTracker&&) noexcept = default;

void BodyTracker::followHeadTurn(const StereoFrame& frame) {
  Impl& m = *impl_;
  if (!options_.capturePose) return;
  const std::optional<hw::HeadAngles> pose = options_.capturePose(frame);
  if (!pose) return;
  const std::optional<hw::HeadAngles> from = std::exchange(m.lastPose, pose);
  if (!from || (from->pan == pose->pan && from->tilt == pose->tilt)) return;
  // Every tracked part is taken at the head's depth: the hands are within
  // an arm's length of it, and a turn moves near and far points alike but
  // for the cameras' small offset from the turning axis.
  const double depth = m.headDepthM > 0 ? m.headDepthM : kUnknownDepthM;
  const auto moved = [&](cv::Point2f p) {
    return pixelAfterHeadTurn(p, depth, *from, *pose, options_.rig);
  };
  for (auto* track : {&m.subject.head, &m.subject.hands[0].track, &m.subject.hands[1].track})
    if (*track) (*track)->shift(moved((*track)->position()) - (*track)->position());
  for (detail::HandTrack& hand : m.subject.hands)
    hand.lastSeen = moved(hand.lastSeen);
}

bool BodyTracker::followBlind(int k, const StereoFrame& frame, cv::Point2f head, double fw,
                              double t) {
  Impl& m = *impl_;
  const TrackerOptions& o = options_;
  if (o.blindFollowS <= 0 || m.looks[k].empty() || t - m.lastDetectedS[k] > o.blindFollowS)
    return false;
  detail::HandTrack& hand = m.subject.hands[static_cast<std::size_t>(k)];
  const cv::Point2f predicted = hand.track->position();
  const double side = k == 0 ? 1.0 : -1.0;  // the person's left hand is on the image's right
  const auto onSide = [&](cv::Point2f at) {
    return (at.x - head.x) * side >= -o.crossFaceWidths * fw;
  };
  const int third = std::max(1, static_cast<int>(fw / 3));
  if (detail::stereoBlindAt(predicted, m.handDisparity[k],
                            detail::validDisparityFraction(frame.disparity, predicted, third), fw,
                            o)) {
    const std::optional<cv::Point2f> at =
        m.looks[k].find(frame.leftGrey, predicted, hand.lastSeen,
                        std::max(1, static_cast<int>(o.blindSearchFaces * fw)), o.blindMinScore);
    if (at && onSide(*at)) {
      hand.track->update(*at);
      hand.lastSeen = *at;
      return true;
    }
  }
  // The hand may have jumped out of the right view, beyond the search
  // around its track: the band is searched where it is near.
  const std::optional<cv::Rect> band = detail::rightViewBandWindow(
      predicted, hand.lastSeen, m.handDisparity[k], fw, frame.leftGrey.size(), o);
  if (!band) return false;
  const std::optional<cv::Point2f> at =
      m.looks[k].findAlikeIn(frame.leftGrey, *band, o.blindMinScore);
  if (!at || !onSide(*at) ||
      !detail::appearedSince(m.looks[k], m.detectedGrey[k], *at,
                             std::max(1, static_cast<int>(kAppearedRadiusFaces * fw)),
                             o.blindMinScore))
    return false;
  // A jump out of the gate restarts the track (an update would turn it
  // into a velocity that throws the next prediction off the image).
  if (hand.track->inGate(*at))
    hand.track->update(*at);
  else
    hand.track.emplace(*at, t, o.hands);
  hand.lastSeen = *at;
  m.bandLook[k] = true;
  return true;
}

void BodyTracker::rememberLook(int k, const HandDetection* detected, const StereoFrame& frame,
                               double fw, double t) {
  Impl& m = *impl_;
  const TrackerOptions& o = options_;
  if (!m.subject.hands[static_cast<std::size_t>(k)].track) {
    m.looks[k].forget();
    return;
  }
  // A small candidate (a hand partly out of the zone, or a speck of clutter
  // that took a near arm's disparity) keeps the last whole hand's look.
  if (!detected || detected->areaPx < o.smallHandAreaFaces * fw * fw ||
      detected->radiusPx < o.smallHandRadiusFaces * fw)
    return;
  const cv::Point2f at = detected->centroid;
  m.looks[k].remember(frame.leftGrey, at, std::max(3, static_cast<int>(o.blindPatchFaces * fw)));
  // Kept for the band search's test that what it finds was not there then
  // (copied: a capture may reuse its buffers; once a frame, for both hands;
  // a fresh buffer, as the other hand may still hold the last one).
  if (o.bandSearchFaces > 0) {
    if (m.greyCopyUpdate != m.updates) {
      m.greyCopy = frame.leftGrey.clone();
      m.greyCopyUpdate = m.updates;
    }
    m.detectedGrey[k] = m.greyCopy;
  }
  m.lastDetectedS[k] = t;
  const int half = std::max(1, static_cast<int>(0.15 * fw));
  const cv::Point3f p = rigPointFromDisparity(
      frame.disparity, o.rig, at,
      cv::Rect(cvRound(at.x) - half, cvRound(at.y) - half, 2 * half + 1, 2 * half + 1));
  m.handDisparity[k] = std::isfinite(p.z) && p.z > 0 ? o.rig.focalPx * o.rig.baseline / p.z : 0;
}

TrackingState BodyTracker::update(const StereoFrame& frame, const Detections& det,
                                  BodySample& body) {
  Impl& m = *impl_;
  const TrackerOptions& o = options_;
  detail::SubjectTracks& s = m.subject;
  ++m.updates;
  const double t = detail::frameTimeS(frame, o, m.clock);
  followHeadTurn(frame);
  detail::predictTracks(s, t);

  // The subject's face, then the election over it.
  const std::optional<bool> seenInside = detail::associateHead(s, det, t, o);
  const ElectionState state = detail::updateElection(m.election, s, seenInside, t, o);

  // Hands: gated nearest-first assignment to the existing tracks, then new
  // tracks from the candidates nearest each hand's resting place.
  if (s.head) {
    detail::HandFrame f = detail::startHandFrame(*s.head, s.faceWidth, det, t, o, s.faceLuma);
    detail::assignGated(s.hands, f, o);
    detail::takePinnedNearHands(s.hands, f, {m.handDisparity[0], m.handDisparity[1]}, o);
    // Where stereo is blind, a hand missed by the detector is followed by
    // its look, before the steps below move it elsewhere.
    detail::followBlindWhereMissed(s.hands, f, [&](int k) {
      const bool found = followBlind(k, frame, f.head, f.fw, t);
      f.steps[static_cast<std::size_t>(k)].lookYields = found && m.bandLook[k];
      return found;
    });
    detail::moveToSolidCandidates(s.hands, f, o);
    detail::reacquireNearLastSeen(s.hands, f, o);
    detail::jumpAfterCoasting(s.hands, f, o);
    detail::coastOrDrop(s.hands, f, o);
    detail::startNewHands(s.hands, f, o);
    for (int k = 0; k < 2; ++k) {
      const detail::HandStep& step = f.steps[static_cast<std::size_t>(k)];
      if (step.detectedBy || !s.hands[static_cast<std::size_t>(k)].track) m.bandLook[k] = false;
      rememberLook(k, step.detectedBy, frame, f.fw, t);
    }
  }

  const TrackingState out =
      detail::reportState(frame, t, state, m.election.candidateS(t), s, o.rig, body);
  if (std::isfinite(out.head.rig.z) && out.head.rig.z > 0) m.headDepthM = out.head.rig.z;
  return out;
}

}  // namespace horopter
