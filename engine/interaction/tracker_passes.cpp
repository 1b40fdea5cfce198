// The tracker's passes; see tracker_passes.hpp.
#include "tracker_passes.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <tuple>

namespace horopter::detail {

bool onHandSide(int k, cv::Point2f c, cv::Point2f head, double fw, const TrackerOptions& o) {
  return (c.x - head.x) * sideSign(k) >= -o.crossFaceWidths * fw;
}

std::optional<std::size_t> nearestFreeCandidate(const std::vector<const HandDetection*>& candidates,
                                                const std::vector<bool>& taken,
                                                const std::function<bool(std::size_t)>& eligible,
                                                cv::Point2f from, std::optional<double> maxDistance,
                                                Ties ties) {
  std::optional<std::size_t> best;
  double bestD = 0;
  for (std::size_t j = 0; j < candidates.size(); ++j) {
    if (taken[j] || !eligible(j)) continue;
    const double d = cv::norm(candidates[j]->centroid - from);
    const bool better = !best ? !maxDistance || d <= *maxDistance
                              : (ties == Ties::HighestIndex ? d <= bestD : d < bestD);
    if (better) best = j, bestD = d;
  }
  return best;
}

void takeCandidate(HandTrack& hand, HandFrame& f, int k, std::size_t j, bool restart,
                   const TrackerOptions& o) {
  const cv::Point2f at = f.candidates[j]->centroid;
  if (restart)
    hand.track.emplace(at, f.t, o.hands);
  else
    hand.track->update(at);
  hand.lastSeen = at;
  HandStep& step = f.steps[static_cast<std::size_t>(k)];
  step.detectedBy = f.candidates[j];
  step.updated = true;
  step.held = j;
  f.taken[j] = true;
}

double frameTimeS(const StereoFrame& frame, const TrackerOptions& o, FrameClock& clock) {
  if (!o.captureTime) return static_cast<double>(frame.index) / o.framesPerSecond;
  if (!clock.haveStart) {
    clock.start = frame.captured;
    clock.haveStart = true;
  }
  return std::chrono::duration<double>(frame.captured - clock.start).count();
}

void predictTracks(SubjectTracks& s, double t) {
  for (auto* track : {&s.head, &s.hands[0].track, &s.hands[1].track})
    if (*track) (*track)->predict(t);
}

const FaceDetection* nearestFaceInGate(const ConstantVelocityTrack& head,
                                       const std::vector<FaceDetection>& faces) {
  const FaceDetection* best = nullptr;
  double bestD = 0;
  for (const FaceDetection& f : faces) {
    if (!head.inGate(f.centre)) continue;
    const double d = head.distance2(f.centre);
    if (!best || d < bestD) best = &f, bestD = d;
  }
  return best;
}

const HandDetection* headSkinBlob(const ConstantVelocityTrack& head, float faceWidth,
                                  const std::vector<HandDetection>& blobs,
                                  const TrackerOptions& o) {
  if (!(o.headBlobFaceWidths > 0)) return nullptr;
  const double fw = std::max(1.0f, faceWidth);
  const HandDetection* blob = nullptr;
  for (const HandDetection& c : blobs)
    if (cv::norm(c.centroid - head.position()) <= o.headBlobFaceWidths * fw &&
        c.areaPx >= 0.3 * fw * fw && c.radiusPx >= 0.2 * fw && (!blob || c.areaPx > blob->areaPx))
      blob = &c;
  return blob;
}

const FaceDetection* largestFaceInside(const std::vector<FaceDetection>& faces) {
  const FaceDetection* best = nullptr;
  for (const FaceDetection& f : faces)
    if (f.insideZone && (!best || f.width > best->width)) best = &f;
  return best;
}

std::optional<bool> associateHead(SubjectTracks& s, const Detections& det, double t,
                                  const TrackerOptions& o) {
  if (!s.head) {
    const FaceDetection* best = largestFaceInside(det.faces);
    if (!best) return std::nullopt;
    s.head.emplace(best->centre, t, o.head);
    s.faceWidth = best->width;
    s.faceLuma = best->skinLuma;
    return true;
  }
  if (const FaceDetection* best = nearestFaceInGate(*s.head, det.faces)) {
    s.head->update(best->centre);
    s.faceWidth = best->width;
    if (best->skinLuma > 0) s.faceLuma = best->skinLuma;
    return best->insideZone;
  }
  // The cascade missed the face: its skin blob (face and neck, large and
  // round, near the prediction) keeps the head's track.
  if (const HandDetection* blob = headSkinBlob(*s.head, s.faceWidth, det.hands, o)) {
    s.head->update(blob->centroid);
    return blob->insideZone;
  }
  s.head->dampVelocity(o.coastVelocityDamping);
  return std::nullopt;
}

ElectionState updateElection(GodfatherElection& election, SubjectTracks& s,
                             std::optional<bool> seenInside, double t, const TrackerOptions& o) {
  const ElectionState state = election.update(t, seenInside);
  if (s.head && t - s.head->lastUpdateS() > o.coastS) s.head.reset();
  if (state == ElectionState::None || !s.head) {
    s.head.reset();
    s.hands[0].track.reset();
    s.hands[1].track.reset();
  }
  return state;
}

bool faceOrNeck(cv::Point2f c, cv::Point2f head, double fw) {
  return std::abs(c.x - head.x) <= 0.5 * fw && c.y - head.y >= -0.6 * fw &&
         c.y - head.y <= 1.2 * fw;
}

std::vector<const HandDetection*> plausibleHandCandidates(
    const std::vector<HandDetection>& hands, cv::Point2f head, double fw, const TrackerOptions& o,
    float faceLuma, std::vector<const HandDetection*>* pinnedOut) {
  std::vector<const HandDetection*> candidates;
  for (const HandDetection& c : hands) {
    // The face and neck themselves, where the detector missed the face this
    // frame (it cuts them out around the faces it finds), are not hands.
    const bool inReach =
        !faceOrNeck(c.centroid, head, fw) && cv::norm(c.centroid - head) <= o.reachFaceWidths * fw;
    const bool handSized = c.areaPx <= o.maxHandAreaFaces * fw * fw &&
                           c.areaPx >= o.minHandAreaFaces * fw * fw &&
                           c.radiusPx >= o.minHandRadiusFaces * fw;
    // A small candidate needs more agreement between the views.
    const bool small =
        c.areaPx < o.smallHandAreaFaces * fw * fw || c.radiusPx < o.smallHandRadiusFaces * fw;
    // A match pinned against the end of the search range is a false one
    // (or a hand nearer than the range, which blind following takes).
    const bool pinned = o.pinnedDisparityFraction > 0 && o.maxDisparityPx > 0 &&
                        c.disparityPx >= o.pinnedDisparityFraction * o.maxDisparityPx;
    // Skin-coloured cloth is far darker than the face's skin under the same light.
    const bool bright = !(faceLuma > 0) || c.meanLuma >= o.minHandLumaOfFace * faceLuma;
    if (inReach && handSized && bright &&
        c.stereoAgreement >= (small ? o.smallHandMinAgreement : o.minStereoAgreement)) {
      if (!pinned)
        candidates.push_back(&c);
      else if (pinnedOut)
        pinnedOut->push_back(&c);
    }
  }
  return candidates;
}

HandFrame startHandFrame(const ConstantVelocityTrack& head, float faceWidth, const Detections& det,
                         double t, const TrackerOptions& o, float faceLuma) {
  HandFrame f;
  f.head = head.position();
  f.fw = std::max(1.0f, faceWidth);
  f.t = t;
  f.candidates = plausibleHandCandidates(det.hands, f.head, f.fw, o, faceLuma, &f.pinned);
  f.taken.assign(f.candidates.size(), false);
  return f;
}

void assignGated(std::array<HandTrack, 2>& hands, HandFrame& f, const TrackerOptions& o) {
  struct Pair {
    double d2;
    int track;
    std::size_t candidate;
  };
  std::vector<Pair> pairs;
  for (int k = 0; k < 2; ++k) {
    const std::optional<ConstantVelocityTrack>& track = hands[static_cast<std::size_t>(k)].track;
    if (!track) continue;
    for (std::size_t j = 0; j < f.candidates.size(); ++j) {
      const cv::Point2f c = f.candidates[j]->centroid;
      if (onHandSide(k, c, f.head, f.fw, o) && track->inGate(c) &&
          cv::norm(c - track->position()) <= o.maxHandStepFaceWidths * f.fw)
        pairs.push_back({track->distance2(c), k, j});
    }
  }
  std::sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) {
    return std::tie(a.d2, a.track, a.candidate) < std::tie(b.d2, b.track, b.candidate);
  });
  for (const Pair& p : pairs) {
    const auto k = static_cast<std::size_t>(p.track);
    if (f.steps[k].updated || f.taken[p.candidate]) continue;
    takeCandidate(hands[k], f, p.track, p.candidate, /*restart=*/false, o);
  }
}

void takePinnedNearHands(std::array<HandTrack, 2>& hands, HandFrame& f,
                         const std::array<double, 2>& handDisparity, const TrackerOptions& o) {
  // A hand brought towards the cameras is matched at the end of the range,
  // like the wood behind a shoulder: a track whose hand was last measured
  // that near may take a whole pinned candidate near it, one that is not
  // cannot, so clutter pinned at the range's end still holds no track.
  if (!(o.pinnedNearFraction > 0) || !(o.maxDisparityPx > 0)) return;
  for (int k = 0; k < 2; ++k) {
    HandTrack& hand = hands[static_cast<std::size_t>(k)];
    const auto ks = static_cast<std::size_t>(k);
    if (!hand.track || f.steps[ks].updated ||
        !(handDisparity[ks] >= o.pinnedNearFraction * o.maxDisparityPx))
      continue;
    const HandDetection* best = nullptr;
    double bestD = 0;
    for (const HandDetection* c : f.pinned) {
      if (std::find(f.candidates.begin(), f.candidates.end(), c) != f.candidates.end()) continue;
      const bool solid = c->areaPx >= o.solidHandAreaFaces * f.fw * f.fw &&
                         c->radiusPx >= o.solidHandRadiusFaces * f.fw;
      const double fromTrack = cv::norm(c->centroid - hand.track->position());
      const double fromSeen = cv::norm(c->centroid - hand.lastSeen);
      const bool near =
          (hand.track->inGate(c->centroid) && fromTrack <= o.maxHandStepFaceWidths * f.fw) ||
          fromSeen <= o.reacquireFaceWidths * f.fw;
      if (!solid || !near || !onHandSide(k, c->centroid, f.head, f.fw, o)) continue;
      const double d = std::min(fromTrack, fromSeen);
      if (!best || d < bestD) best = c, bestD = d;
    }
    if (!best) continue;
    // It joins the frame's candidates, taken, so no later pass moves another track onto it.
    f.candidates.push_back(best);
    f.taken.push_back(false);
    takeCandidate(hand, f, k, f.candidates.size() - 1,
                  /*restart=*/!hand.track->inGate(best->centroid), o);
  }
}

bool stereoBlindAt(cv::Point2f predicted, double handDisparity, double validFraction, double fw,
                   const TrackerOptions& o) {
  // Only where the front end indeed found no depth: a blob of clutter that
  // block matching pulled forward beside a near arm is not blind.
  if (validFraction >= o.blindValidFraction) return false;
  const double d = handDisparity;
  const bool outOfRightView = d > 0 && predicted.x < d + o.blindBandFaces * fw;
  const bool tooNear = d > 0 && o.maxDisparityPx > 0 && d > o.blindNearFraction * o.maxDisparityPx;
  return outOfRightView || tooNear || o.blindTextureless > 0;
}

std::optional<cv::Rect> rightViewBandWindow(cv::Point2f predicted, cv::Point2f lastSeen,
                                            double handDisparity, double fw, cv::Size image,
                                            const TrackerOptions& o) {
  if (!(o.bandSearchFaces > 0) || !(handDisparity > 0)) return std::nullopt;
  const double edge = handDisparity + o.blindBandFaces * fw;  // the band is left of it
  if (std::min(predicted.x, lastSeen.x) > edge + o.bandSearchFaces * fw) return std::nullopt;
  const double top = std::min(predicted.y, lastSeen.y) - fw;
  const double bottom = std::max(predicted.y, lastSeen.y) + fw;
  const cv::Rect band(0, cvFloor(top), cvCeil(edge), cvFloor(bottom) - cvFloor(top) + 1);
  const cv::Rect window = band & cv::Rect(0, 0, image.width, image.height);
  if (window.empty()) return std::nullopt;
  return window;
}

void followBlindWhereMissed(const std::array<HandTrack, 2>& hands, HandFrame& f,
                            const std::function<bool(int)>& follow) {
  for (int k = 0; k < 2; ++k) {
    HandStep& step = f.steps[static_cast<std::size_t>(k)];
    if (hands[static_cast<std::size_t>(k)].track && !step.updated)
      step.updated = step.followedBlind = follow(k);
  }
}

bool solidCandidate(const HandFrame& f, std::size_t j, const TrackerOptions& o) {
  return f.candidates[j]->areaPx >= o.solidHandAreaFaces * f.fw * f.fw &&
         f.candidates[j]->radiusPx >= o.solidHandRadiusFaces * f.fw;
}

void moveToSolidCandidates(std::array<HandTrack, 2>& hands, HandFrame& f, const TrackerOptions& o) {
  // A track held by a weak candidate (a speck of clutter it fell onto when
  // the hand outran its gate), or by none, moves to a free solid one on
  // its side: a whole hand is both larger and rounder than the specks.
  if (!(o.solidHandAreaFaces > 0)) return;
  for (int k = 0; k < 2; ++k) {
    HandTrack& hand = hands[static_cast<std::size_t>(k)];
    HandStep& step = f.steps[static_cast<std::size_t>(k)];
    // A look found by searching the whole band may be a false match there
    // (a look is no proof): a whole hand on its side outweighs it.
    if (!hand.track || (step.followedBlind && !step.lookYields) ||
        (step.held && solidCandidate(f, *step.held, o)))
      continue;
    const std::optional<std::size_t> best = nearestFreeCandidate(
        f.candidates, f.taken,
        [&](std::size_t j) {
          return onHandSide(k, f.candidates[j]->centroid, f.head, f.fw, o) &&
                 solidCandidate(f, j, o);
        },
        hand.track->position());
    if (!best) continue;
    if (step.held) f.taken[*step.held] = false;
    step.followedBlind = step.lookYields = false;
    takeCandidate(hand, f, k, *best, /*restart=*/true, o);
  }
}

void reacquireNearLastSeen(std::array<HandTrack, 2>& hands, HandFrame& f, const TrackerOptions& o) {
  // A hand that left its gate (hands start and stop faster than any
  // constant-velocity model expects) is taken up again at the free
  // candidate nearest where it was last seen, within reacquireFaceWidths.
  // Of equally near candidates the last wins.
  for (int k = 0; k < 2; ++k) {
    HandTrack& hand = hands[static_cast<std::size_t>(k)];
    if (!hand.track || f.steps[static_cast<std::size_t>(k)].updated) continue;
    const std::optional<std::size_t> best = nearestFreeCandidate(
        f.candidates, f.taken,
        [&](std::size_t j) { return onHandSide(k, f.candidates[j]->centroid, f.head, f.fw, o); },
        hand.lastSeen, o.reacquireFaceWidths * f.fw, Ties::HighestIndex);
    if (best) takeCandidate(hand, f, k, *best, /*restart=*/true, o);
  }
}

void jumpAfterCoasting(std::array<HandTrack, 2>& hands, HandFrame& f, const TrackerOptions& o) {
  // A track that has coasted for a while (the hand jumped out of its gate
  // and reach, a pointing arm say) gives way to the free candidate on its
  // side nearest to it, rather than waiting to be dropped.
  if (!(o.coastJumpS > 0)) return;
  for (int k = 0; k < 2; ++k) {
    HandTrack& hand = hands[static_cast<std::size_t>(k)];
    if (!hand.track || f.steps[static_cast<std::size_t>(k)].updated ||
        f.t - hand.track->lastUpdateS() <= o.coastJumpS)
      continue;
    const std::optional<std::size_t> best = nearestFreeCandidate(
        f.candidates, f.taken,
        [&](std::size_t j) { return onHandSide(k, f.candidates[j]->centroid, f.head, f.fw, o); },
        hand.track->position());
    if (best) takeCandidate(hand, f, k, *best, /*restart=*/true, o);
  }
}

void coastOrDrop(std::array<HandTrack, 2>& hands, const HandFrame& f, const TrackerOptions& o) {
  for (std::size_t k = 0; k < 2; ++k) {
    std::optional<ConstantVelocityTrack>& track = hands[k].track;
    if (!track || f.steps[k].updated) continue;
    track->dampVelocity(o.coastVelocityDamping);
    if (f.t - track->lastUpdateS() > o.coastS) track.reset();
  }
}

cv::Point2f restPlace(int k, cv::Point2f head, double fw) {
  // The person's left hand appears on the image's right.
  return {static_cast<float>(head.x + sideSign(k) * 1.4 * fw),
          static_cast<float>(head.y + 4.3 * fw)};
}

void startNewHands(std::array<HandTrack, 2>& hands, HandFrame& f, const TrackerOptions& o) {
  for (int k = 0; k < 2; ++k) {
    HandTrack& hand = hands[static_cast<std::size_t>(k)];
    if (hand.track) continue;
    const std::optional<std::size_t> best = nearestFreeCandidate(
        f.candidates, f.taken,
        [&](std::size_t j) {
          return !((f.candidates[j]->centroid.x - f.head.x) * sideSign(k) < 0);
        },
        restPlace(k, f.head, f.fw));
    if (best) takeCandidate(hand, f, k, *best, /*restart=*/true, o);
  }
}

PartState partOf(const std::optional<ConstantVelocityTrack>& track, double timeS,
                 const StereoFrame& frame, const RectifiedGeometry& rig, int windowPx) {
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

TrackingState reportState(const StereoFrame& frame, double t, ElectionState state,
                          double candidateS, const SubjectTracks& s, const RectifiedGeometry& rig,
                          BodySample& body) {
  TrackingState out;
  out.timeS = t;
  out.election = state;
  out.candidateS = candidateS;
  out.faceWidthPx = s.head ? s.faceWidth : 0;
  body = BodySample{};
  body.frame = frame.index;
  body.timeS = t;
  body.godfather = state == ElectionState::Godfather && s.head.has_value();
  const int faceWindow = std::max(3, static_cast<int>(0.5f * s.faceWidth));
  out.head = partOf(s.head, t, frame, rig, faceWindow);
  out.leftHand = partOf(s.hands[0].track, t, frame, rig, std::max(3, faceWindow / 2));
  out.rightHand = partOf(s.hands[1].track, t, frame, rig, std::max(3, faceWindow / 2));
  if (body.godfather) {
    body.head = out.head;
    body.leftHand = out.leftHand;
    body.rightHand = out.rightHand;
  }
  if (out.head.tracked && out.leftHand.tracked && out.rightHand.tracked)
    out.triangle = bodyTriangle(out.head.image, out.leftHand.image, out.rightHand.image);
  return out;
}

}  // namespace horopter::detail
