// The godfather's election and Kalman tracks of head and hands; see
// horopter/tracking.hpp.
#include "horopter/tracking.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "blind_follow.hpp"
#include "horopter/error.hpp"
#include "horopter/head_control.hpp"

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
  std::optional<ConstantVelocityTrack> head, hands[2];  // hands: [0] left, [1] right (the person's)
  cv::Point2f lastSeen[2];                              // where each hand was last observed
  detail::PatchFollower looks[2];  // each hand's last detected patch, for where stereo is blind
  double lastDetectedS[2] = {0, 0};
  double handDisparity[2] = {0, 0};  // px, where last detected (0: unknown)
  float faceWidth = 0;
  std::optional<hw::HeadAngles> lastPose;  // the previous frame's, with capturePose
  double headDepthM = 0;                   // the head's last measured depth (0: none yet)
  bool haveStart = false;
  SteadyClock::time_point start{};
};

namespace {

// The depth a turn is undone at before the head's depth is measured.
constexpr double kUnknownDepthM = 1.5;

void validate(const TrackerOptions& o) {
  if (!(o.coastS >= 0) || !(o.coastJumpS >= 0) || !(o.reachFaceWidths > 0) ||
      !(o.maxHandAreaFaces > o.minHandAreaFaces) || o.minHandAreaFaces < 0)
    throw Error("tracker coast and coast-jump times must be >= 0 s, reach and hand area > 0");
  if (!(o.minHandRadiusFaces >= 0) || !(o.crossFaceWidths >= 0) || !(o.solidHandAreaFaces >= 0) ||
      !(o.solidHandRadiusFaces >= 0) || !(o.headBlobFaceWidths >= 0))
    throw Error(
        "tracker hand radius, crossing, solid-hand and head-blob limits must be >= 0 face widths");
  if (!(o.minStereoAgreement >= 0 && o.minStereoAgreement <= 1) ||
      !(o.smallHandMinAgreement >= 0 && o.smallHandMinAgreement <= 1) ||
      !(o.smallHandAreaFaces >= 0) || !(o.smallHandRadiusFaces >= 0))
    throw Error("tracker stereo agreements must be fractions in [0, 1] and small-hand limits >= 0");
  if (!(o.blindFollowS >= 0) || !(o.blindBandFaces >= 0) || !(o.blindNearFraction > 0) ||
      !(o.blindValidFraction >= 0 && o.blindValidFraction <= 1) || !(o.blindPatchFaces > 0) ||
      !(o.blindSearchFaces > 0) || !(o.blindMinScore >= -1 && o.blindMinScore <= 1) ||
      !(o.maxDisparityPx >= 0))
    throw Error(
        "tracker blind following needs times, band and largest disparity >= 0, a near fraction, "
        "patch and search sizes > 0, a valid fraction in [0, 1] and a score in [-1, 1]");
  if (!(o.framesPerSecond > 0) || !std::isfinite(o.framesPerSecond))
    throw Error("tracker framesPerSecond must be positive");
}

PartState partOf(const std::optional<ConstantVelocityTrack>& track, double timeS,
                 const Frame& frame, const RectifiedGeometry& rig, int windowPx) {
  PartState p;
  if (!track) return p;
  p.tracked = true;
  p.observed = track->lastUpdateS() == timeS;
  p.image = track->position();
  const int h = std::max(1, windowPx / 2);
  p.rig = rigPointFromDisparity(
      frame.disparity, rig, p.image,
      cv::Rect(cvRound(p.image.x) - h, cvRound(p.image.y) - h, 2 * h + 1, 2 * h + 1));
  return p;
}

}  // namespace

BodyTracker::BodyTracker(TrackerOptions options) : options_(options) {
  validate(options_);
  impl_ = std::make_unique<Impl>(options_);
}
BodyTracker::~BodyTracker() = default;
BodyTracker::BodyTracker(BodyTracker&&) noexcept = default;

void BodyTracker::followHeadTurn(const Frame& frame) {
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
  for (auto* track : {&m.head, &m.hands[0], &m.hands[1]})
    if (*track) (*track)->shift(moved((*track)->position()) - (*track)->position());
  for (cv::Point2f& seen : m.lastSeen)
    seen = moved(seen);
}

bool BodyTracker::followBlind(int k, const Frame& frame, cv::Point2f head, double fw, double t) {
  Impl& m = *impl_;
  const TrackerOptions& o = options_;
  if (o.blindFollowS <= 0 || m.looks[k].empty() || t - m.lastDetectedS[k] > o.blindFollowS)
    return false;
  const cv::Point2f predicted = m.hands[k]->position();
  const double d = m.handDisparity[k];
  const bool outOfRightView = d > 0 && predicted.x < d + o.blindBandFaces * fw;
  const bool tooNear = d > 0 && o.maxDisparityPx > 0 && d > o.blindNearFraction * o.maxDisparityPx;
  // ... and where the front end indeed found no depth: a blob of clutter
  // that block matching pulled forward beside a near arm is not blind.
  const int third = std::max(1, static_cast<int>(fw / 3));
  if ((!outOfRightView && !tooNear) ||
      detail::validDisparityFraction(frame.disparity, predicted, third) >= o.blindValidFraction)
    return false;
  const std::optional<cv::Point2f> at =
      m.looks[k].find(frame.leftGrey, predicted, m.lastSeen[k],
                      std::max(1, static_cast<int>(o.blindSearchFaces * fw)), o.blindMinScore);
  const double side = k == 0 ? 1.0 : -1.0;  // the person's left hand is on the image's right
  if (!at || (at->x - head.x) * side < -o.crossFaceWidths * fw) return false;
  m.hands[k]->update(*at);
  m.lastSeen[k] = *at;
  return true;
}

void BodyTracker::rememberLook(int k, const HandDetection* detected, const Frame& frame, double fw,
                               double t) {
  Impl& m = *impl_;
  const TrackerOptions& o = options_;
  if (!m.hands[k]) {
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
  m.lastDetectedS[k] = t;
  const int half = std::max(1, static_cast<int>(0.15 * fw));
  const cv::Point3f p = rigPointFromDisparity(
      frame.disparity, o.rig, at,
      cv::Rect(cvRound(at.x) - half, cvRound(at.y) - half, 2 * half + 1, 2 * half + 1));
  m.handDisparity[k] = std::isfinite(p.z) && p.z > 0 ? o.rig.focalPx * o.rig.baseline / p.z : 0;
}

TrackingState BodyTracker::update(const Frame& frame, BodySample& body) {
  if (!frame.detections)
    throw Error("tracking needs Frame::detections: run the detection stage first");
  const Detections& det = *frame.detections;
  Impl& m = *impl_;
  const TrackerOptions& o = options_;
  double t = static_cast<double>(frame.index) / o.framesPerSecond;
  if (o.captureTime) {
    if (!m.haveStart) {
      m.start = frame.captured;
      m.haveStart = true;
    }
    t = std::chrono::duration<double>(frame.captured - m.start).count();
  }
  followHeadTurn(frame);
  for (auto* track : {&m.head, &m.hands[0], &m.hands[1]})
    if (*track) (*track)->predict(t);

  // The subject's face: the gated detection nearest the head track, or a new
  // subject (the largest face inside the zone) when there is no track.
  std::optional<bool> seenInside;
  if (m.head) {
    const FaceDetection* best = nullptr;
    double bestD = 0;
    for (const FaceDetection& f : det.faces) {
      if (!m.head->inGate(f.centre)) continue;
      const double d = m.head->distance2(f.centre);
      if (!best || d < bestD) best = &f, bestD = d;
    }
    // The cascade missed the face: its skin blob (face and neck, large and
    // round, near the prediction) keeps the head's track.
    const HandDetection* blob = nullptr;
    if (!best && o.headBlobFaceWidths > 0) {
      const double fw = std::max(1.0f, m.faceWidth);
      for (const HandDetection& c : det.hands)
        if (cv::norm(c.centroid - m.head->position()) <= o.headBlobFaceWidths * fw &&
            c.areaPx >= 0.3 * fw * fw && c.radiusPx >= 0.2 * fw &&
            (!blob || c.areaPx > blob->areaPx))
          blob = &c;
    }
    if (best) {
      m.head->update(best->centre);
      m.faceWidth = best->width;
      seenInside = best->insideZone;
    } else if (blob) {
      m.head->update(blob->centroid);
      seenInside = blob->insideZone;
    } else {
      m.head->dampVelocity(o.coastVelocityDamping);
    }
  } else {
    const FaceDetection* best = nullptr;
    for (const FaceDetection& f : det.faces)
      if (f.insideZone && (!best || f.width > best->width)) best = &f;
    if (best) {
      m.head.emplace(best->centre, t, o.head);
      m.faceWidth = best->width;
      seenInside = true;
    }
  }
  const ElectionState state = m.election.update(t, seenInside);
  if (m.head && t - m.head->lastUpdateS() > o.coastS) m.head.reset();
  if (state == ElectionState::None || !m.head) {
    m.head.reset();
    m.hands[0].reset();
    m.hands[1].reset();
  }

  // Hands: gated nearest-first assignment to the existing tracks, then new
  // tracks from the candidates nearest each hand's resting place.
  if (m.head) {
    const cv::Point2f h = m.head->position();
    const double fw = std::max(1.0f, m.faceWidth);
    std::vector<const HandDetection*> candidates;
    // The face and neck themselves, where the detector missed the face this
    // frame (it cuts them out around the faces it finds).
    auto faceOrNeck = [&](cv::Point2f c) {
      return std::abs(c.x - h.x) <= 0.5 * fw && c.y - h.y >= -0.6 * fw && c.y - h.y <= 1.2 * fw;
    };
    for (const HandDetection& c : det.hands)
      if (!faceOrNeck(c.centroid) && cv::norm(c.centroid - h) <= o.reachFaceWidths * fw &&
          c.areaPx <= o.maxHandAreaFaces * fw * fw && c.areaPx >= o.minHandAreaFaces * fw * fw &&
          c.radiusPx >= o.minHandRadiusFaces * fw &&
          c.stereoAgreement >=
              (c.areaPx < o.smallHandAreaFaces * fw * fw || c.radiusPx < o.smallHandRadiusFaces * fw
                   ? o.smallHandMinAgreement
                   : o.minStereoAgreement))
        candidates.push_back(&c);
    // Whether candidate j may be hand k: not far on the other hand's side.
    auto onSide = [&](int k, std::size_t j) {
      const double side = k == 0 ? 1.0 : -1.0;  // the person's left hand is on the image's right
      return (candidates[j]->centroid.x - h.x) * side >= -o.crossFaceWidths * fw;
    };
    std::vector<bool> taken(candidates.size(), false);
    struct Pair {
      double d2;
      int track;
      std::size_t candidate;
    };
    std::vector<Pair> pairs;
    for (int k = 0; k < 2; ++k)
      if (m.hands[k])
        for (std::size_t j = 0; j < candidates.size(); ++j)
          if (onSide(k, j) && m.hands[k]->inGate(candidates[j]->centroid) &&
              cv::norm(candidates[j]->centroid - m.hands[k]->position()) <=
                  o.maxHandStepFaceWidths * fw)
            pairs.push_back({m.hands[k]->distance2(candidates[j]->centroid), k, j});
    std::sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) {
      return std::tie(a.d2, a.track, a.candidate) < std::tie(b.d2, b.track, b.candidate);
    });
    bool updated[2] = {false, false};
    std::size_t assigned[2] = {candidates.size(), candidates.size()};
    const HandDetection* detectedBy[2] = {nullptr, nullptr};  // this frame's candidate
    for (const Pair& p : pairs) {
      if (updated[p.track] || taken[p.candidate]) continue;
      m.hands[p.track]->update(candidates[p.candidate]->centroid);
      m.lastSeen[p.track] = candidates[p.candidate]->centroid;
      detectedBy[p.track] = candidates[p.candidate];
      updated[p.track] = taken[p.candidate] = true;
      assigned[p.track] = p.candidate;
    }
    // Where stereo is blind, a hand missed by the detector is followed by
    // its look, before the steps below move it elsewhere.
    bool followedBlind[2] = {false, false};
    for (int k = 0; k < 2; ++k)
      if (m.hands[k] && !updated[k])
        updated[k] = followedBlind[k] = followBlind(k, frame, h, fw, t);
    // A track held by a weak candidate (a speck of clutter it fell onto when
    // the hand outran its gate), or by none, moves to a free solid one on
    // its side: a whole hand is both larger and rounder than the specks.
    auto solid = [&](std::size_t j) {
      return candidates[j]->areaPx >= o.solidHandAreaFaces * fw * fw &&
             candidates[j]->radiusPx >= o.solidHandRadiusFaces * fw;
    };
    for (int k = 0; k < 2 && o.solidHandAreaFaces > 0; ++k) {
      if (!m.hands[k] || followedBlind[k] || (updated[k] && solid(assigned[k]))) continue;
      std::size_t best = candidates.size();
      double bestD = 0;
      for (std::size_t j = 0; j < candidates.size(); ++j) {
        if (taken[j] || !onSide(k, j) || !solid(j)) continue;
        const double d = cv::norm(candidates[j]->centroid - m.hands[k]->position());
        if (best == candidates.size() || d < bestD) best = j, bestD = d;
      }
      if (best == candidates.size()) continue;
      if (updated[k]) taken[assigned[k]] = false;
      m.hands[k].emplace(candidates[best]->centroid, t, o.hands);
      m.lastSeen[k] = candidates[best]->centroid;
      detectedBy[k] = candidates[best];
      updated[k] = taken[best] = true;
      assigned[k] = best;
    }
    // A hand that left its gate (hands start and stop faster than any
    // constant-velocity model expects) is taken up again at the free
    // candidate nearest where it was last seen, within reacquireFaceWidths.
    for (int k = 0; k < 2; ++k) {
      if (!m.hands[k] || updated[k]) continue;
      std::size_t best = candidates.size();
      double bestD = o.reacquireFaceWidths * fw;
      for (std::size_t j = 0; j < candidates.size(); ++j) {
        const double d = cv::norm(candidates[j]->centroid - m.lastSeen[k]);
        if (!taken[j] && onSide(k, j) && d <= bestD) best = j, bestD = d;
      }
      if (best < candidates.size()) {
        m.hands[k].emplace(candidates[best]->centroid, t, o.hands);
        m.lastSeen[k] = candidates[best]->centroid;
        detectedBy[k] = candidates[best];
        updated[k] = taken[best] = true;
      }
    }
    // A track that has coasted for a while (the hand jumped out of its gate
    // and reach, a pointing arm say) gives way to the free candidate on its
    // side nearest to it, rather than waiting to be dropped.
    for (int k = 0; k < 2 && o.coastJumpS > 0; ++k) {
      if (!m.hands[k] || updated[k] || t - m.hands[k]->lastUpdateS() <= o.coastJumpS) continue;
      std::size_t best = candidates.size();
      double bestD = 0;
      for (std::size_t j = 0; j < candidates.size(); ++j) {
        const double d = cv::norm(candidates[j]->centroid - m.hands[k]->position());
        if (!taken[j] && onSide(k, j) && (best == candidates.size() || d < bestD))
          best = j, bestD = d;
      }
      if (best < candidates.size()) {
        m.hands[k].emplace(candidates[best]->centroid, t, o.hands);
        m.lastSeen[k] = candidates[best]->centroid;
        detectedBy[k] = candidates[best];
        updated[k] = taken[best] = true;
      }
    }
    for (int k = 0; k < 2; ++k) {
      if (m.hands[k] && !updated[k]) m.hands[k]->dampVelocity(o.coastVelocityDamping);
      if (m.hands[k] && !updated[k] && t - m.hands[k]->lastUpdateS() > o.coastS) m.hands[k].reset();
      if (m.hands[k]) continue;
      // The person's left hand appears on the image's right.
      const double side = k == 0 ? 1.0 : -1.0;
      const cv::Point2f rest(static_cast<float>(h.x + side * 1.4 * fw),
                             static_cast<float>(h.y + 4.3 * fw));
      std::size_t best = candidates.size();
      double bestD = 0;
      for (std::size_t j = 0; j < candidates.size(); ++j) {
        if (taken[j] || (candidates[j]->centroid.x - h.x) * side < 0) continue;
        const double d = cv::norm(candidates[j]->centroid - rest);
        if (best == candidates.size() || d < bestD) best = j, bestD = d;
      }
      if (best < candidates.size()) {
        m.hands[k].emplace(candidates[best]->centroid, t, o.hands);
        m.lastSeen[k] = candidates[best]->centroid;
        detectedBy[k] = candidates[best];
        taken[best] = true;
      }
    }
    for (int k = 0; k < 2; ++k)
      rememberLook(k, detectedBy[k], frame, fw, t);
  }

  TrackingState s;
  s.timeS = t;
  s.election = state;
  s.candidateS = m.election.candidateS(t);
  s.faceWidthPx = m.head ? m.faceWidth : 0;
  body = BodySample{};
  body.frame = frame.index;
  body.timeS = t;
  body.godfather = state == ElectionState::Godfather && m.head.has_value();
  const int faceWindow = std::max(3, static_cast<int>(0.5f * m.faceWidth));
  s.head = partOf(m.head, t, frame, o.rig, faceWindow);
  if (std::isfinite(s.head.rig.z) && s.head.rig.z > 0) m.headDepthM = s.head.rig.z;
  s.leftHand = partOf(m.hands[0], t, frame, o.rig, std::max(3, faceWindow / 2));
  s.rightHand = partOf(m.hands[1], t, frame, o.rig, std::max(3, faceWindow / 2));
  if (body.godfather) {
    body.head = s.head;
    body.leftHand = s.leftHand;
    body.rightHand = s.rightHand;
  }
  if (s.head.tracked && s.leftHand.tracked && s.rightHand.tracked)
    s.triangle = bodyTriangle(s.head.image, s.leftHand.image, s.rightHand.image);
  return s;
}

namespace {

class TrackingStage : public Stage {
 public:
  explicit TrackingStage(TrackerOptions options) : tracker_(options) {}
  std::string name() const override { return "tracking"; }
  void process(Frame& frame) override {
    frame.tracking = std::make_shared<const TrackingState>(tracker_.update(frame, frame.body));
  }

 private:
  BodyTracker tracker_;
};

}  // namespace

std::unique_ptr<Stage> makeTrackingStage(TrackerOptions options) {
  return std::make_unique<TrackingStage>(options);
}

}  // namespace horopter
