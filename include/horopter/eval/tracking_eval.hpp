// Tracking trials on the synthetic scene (horopter eval-tracking, and
// horopter eval-interaction for movement analysis): one trial renders a
// varied scene (distance, lighting, sensor noise, skin-coloured clutter, a
// distractor outside the zone) and runs the whole pipeline on it, closed loop
// with the head, then scores tracking against the scene's truth.
//
// Scores:
//  - tracker loss: among the frames where the truth has a godfather (the main
//    person inside the zone for election.electS, by the same election rule on
//    the truth), the fraction where the head or a hand that is visible has no
//    track of the godfather's, or a track further than max(20 px, half the face
//    width) from it.
//  - false-positive rate: detections (faces and hand candidates) that are not
//    the head or a hand of a person inside the zone (within the same
//    distance), over all detections.
#pragma once

#include <cstdint>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "horopter/app/frame.hpp"
#include "horopter/app/vision_stages.hpp"
#include "horopter/interaction/detection.hpp"
#include "horopter/interaction/head_control.hpp"
#include "horopter/interaction/tracking.hpp"
#include "horopter/kernels/stereo_params.hpp"
#include "horopter/sim/synthetic_scene.hpp"

namespace horopter {

struct TrialOptions {
  std::uint64_t seed = 1;  // the trial's scene (and its variations)
  int frames = 300;
  int width = 640, height = 480;
  std::string backend = "auto";  // the front end's backend
  int threads = 1;               // the disparity stage's threads
  int inFlight = 3;
  // The front end: 128 disparities reach 0.52 m, nearer than hands pushed
  // forward from 1.0-1.7 m come (96 stopped at 0.7 m, 64 at 1.04 m); the
  // left band matched where at least 16 disparities fit, so that the longer
  // range does not widen the columns the matcher leaves blind (issue 20:
  // tuning blocks 10596-10627 4.70 -> 3.38 % lost frames, 10660-10691 3.74
  // -> 2.37 %; engine/interaction/README.md).
  StereoParams stereo = [] {
    StereoParams p;
    p.numDisparities = 128;
    p.leftBand = 16;
    return p;
  }();
  MedianParams median;
  ZoneSearch zoneSearch;    // each frame's search range from its zone (off: the full range)
  bool headControl = true;  // closed loop; false: the head stays where it starts
  // The tracks move with the image when the head turns (the tracker is given
  // each frame's head pose; TrackerOptions::capturePose).
  bool followHeadTurns = true;
  DetectorOptions detector;  // its scope is set by the run
  TrackerOptions tracker;    // its rig and rate come from the scene
  HeadControlOptions head;
};

// The scene of a trial: SceneOptions with the person's distance (1.0-1.7 m),
// lighting gain (0.7-1.3), sensor noise (0-6 grey levels) drawn from the
// seed, skin-coloured clutter and the distractor.
synth::SceneOptions trialScene(const TrialOptions& options);

struct PartScore {
  std::int64_t visible = 0;  // godfather frames where the part is visible
  std::int64_t lost = 0;
};

// What a trial's per-frame callback sees (after the last stage).
struct TrialFrame {
  const Frame& frame;
  const synth::FrameTruth& truth;
  bool truthGodfather = false;        // the main person is the godfather by the truth
  bool lost = false;                  // counted as a tracker-loss frame
  bool partLost[3] = {};              // head, left hand, right hand: visible and lost
  double focalPx = 0, baselineM = 0;  // the scene's rectified rig
};
using TrialFrameCallback = std::function<void(const TrialFrame&)>;

struct TrialResult {
  std::uint64_t seed = 0;
  DetectionScope scope = DetectionScope::HoropterRegion;
  std::int64_t frames = 0;
  std::int64_t godfatherFrames = 0;  // frames with a godfather by the truth
  std::int64_t lostFrames = 0;
  PartScore head, leftHand, rightHand;
  std::int64_t detections = 0, falseDetections = 0;
  RunSummary summary;  // the pipeline's (stage times, frames/s)
  double trackerLoss() const;
  double falsePositiveRate() const;
  double stageMs(const std::string& name) const;  // 0 when the stage did not run
};

// Runs one trial. `extraStages` run after tracking and head control (they
// see Frame::body); `onFrame` is called for every finished frame, in order.
// Throws horopter::Error for bad options.
TrialResult runTrackingTrial(const TrialOptions& options, DetectionScope scope,
                             std::vector<std::unique_ptr<Stage>> extraStages = {},
                             TrialFrameCallback onFrame = {});

// Why a part was lost in a frame (horopter eval-tracking --diagnose): the
// first cause that holds, in this order.
enum class LossCause {
  NoGodfather,  // the tracker has no elected godfather (election late, or head lost)
  // No detection near the truth (within the scorer's tolerance):
  BarelyVisible,  // under a third of the hand's disc shows the hand (truth's occlusion)
  RightViewOut,   // the part's centre is outside the right view (x < its disparity): no
                  // stereo, so no zone there, though the left image shows it
  NoDisparity,    // no valid disparity on most of the part's disc (nearer than the search
                  // range, or textureless), so no zone there
  OutsideMask,    // the zone's mask covers under a third of the part's disc
  FaceNeckCut,    // the part lies in a face's face-and-neck exclusion box
  Merged,         // a hand candidate's box holds the part but its centroid is elsewhere
  NoSkin,         // the skin model finds under a fifth of the part's disc
  Removed,        // skin there, but opened away or under the smallest area
  // A detection near the truth:
  Filtered,   // the tracker's reach or area limits refused it
  NoTrack,    // no track for the part
  Swapped,    // the part's track is on the other hand
  Elsewhere,  // the track is elsewhere (neck, clutter, a stale position)
  Count
};
const char* lossCauseName(LossCause cause);

struct LossDiagnosis {
  // [part][cause]: part 0 head, 1 left hand, 2 right hand.
  std::int64_t counts[3][static_cast<int>(LossCause::Count)] = {};
  // When set, one line per lost part: the cause, the truth, the track and
  // the hand candidates.
  std::FILE* log = nullptr;
  // Adds the causes of the lost parts of one scored frame.
  void add(const TrialFrame& frame, const TrialOptions& options);
};

// Several trials of one scope, summed.
struct ScopeScore {
  DetectionScope scope = DetectionScope::HoropterRegion;
  int trials = 0;
  std::int64_t frames = 0, godfatherFrames = 0, lostFrames = 0;
  PartScore head, leftHand, rightHand;
  std::int64_t detections = 0, falseDetections = 0;
  double seconds = 0;      // wall time of the pipelines
  double detectionMs = 0;  // mean per frame
  double trackingMs = 0;
  double visionMs = 0;  // every stage but capture (rendering), per frame
  double trackerLoss() const;
  double falsePositiveRate() const;
  double fps() const;  // frames / seconds, rendering included
  void add(const TrialResult& trial);
};

}  // namespace horopter
