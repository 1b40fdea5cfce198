// Tracking trials on the synthetic scene and their scores; see
// horopter/eval/tracking_eval.hpp.
#include "horopter/eval/tracking_eval.hpp"

#include <algorithm>
#include <cmath>

#include "horopter/app/pipeline_builder.hpp"
#include "horopter/core/error.hpp"
#include "horopter/kernels/backend.hpp"
#include "horopter/sim/sim_frame.hpp"
#include "horopter/sim/synthetic_source.hpp"
#include "horopter/vision/geometry.hpp"
#include "synthetic/rng.hpp"

namespace horopter {

synth::SceneOptions trialScene(const TrialOptions& o) {
  synth::SceneOptions s;
  s.width = o.width;
  s.height = o.height;
  s.seed = o.seed;
  synth::SplitMix64 rng(o.seed * 0xD1B54A32D192ED03ull + 17);
  s.personDistanceM = rng.uniform(1.0, 1.7);
  s.lightingGain = rng.uniform(0.7, 1.3);
  s.sensorNoiseSigma = rng.uniform(0.0, 6.0);
  s.skinClutter = true;
  s.distractor = true;
  return s;
}

double TrialResult::trackerLoss() const {
  return godfatherFrames > 0 ? static_cast<double>(lostFrames) / godfatherFrames : 0;
}
double TrialResult::falsePositiveRate() const {
  return detections > 0 ? static_cast<double>(falseDetections) / detections : 0;
}
double TrialResult::stageMs(const std::string& name) const {
  for (const StageSummary& s : summary.stages)
    if (s.name == name) return s.meanMs;
  return 0;
}

double ScopeScore::trackerLoss() const {
  return godfatherFrames > 0 ? static_cast<double>(lostFrames) / godfatherFrames : 0;
}
double ScopeScore::falsePositiveRate() const {
  return detections > 0 ? static_cast<double>(falseDetections) / detections : 0;
}
double ScopeScore::fps() const {
  return seconds > 0 ? frames / seconds : 0;
}

void ScopeScore::add(const TrialResult& t) {
  scope = t.scope;
  const double before = static_cast<double>(frames), n = static_cast<double>(t.summary.completed);
  auto mean = [&](double sum, double value) {
    return (sum * before + value * n) / std::max(1.0, before + n);
  };
  double vision = 0;
  for (const StageSummary& s : t.summary.stages)
    if (s.name.rfind("capture", 0) != 0) vision += s.meanMs;
  detectionMs = mean(detectionMs, t.stageMs("detection"));
  trackingMs = mean(trackingMs, t.stageMs("tracking"));
  visionMs = mean(visionMs, vision);
  ++trials;
  frames += t.summary.completed;
  godfatherFrames += t.godfatherFrames;
  lostFrames += t.lostFrames;
  for (auto [sum, part] : {std::pair{&head, &t.head}, std::pair{&leftHand, &t.leftHand},
                           std::pair{&rightHand, &t.rightHand}}) {
    sum->visible += part->visible;
    sum->lost += part->lost;
  }
  detections += t.detections;
  falseDetections += t.falseDetections;
  seconds += t.summary.seconds;
}

namespace {

// A hand is visible when it lies in view (its centre at least its radius,
// about 0.3 face widths, inside the image) and nothing nearer hides its
// centre (the truth's surface there is not in front of the hand's front by
// more than a few centimetres).
bool handVisible(const synth::FrameTruth& truth, cv::Point2f p2, const cv::Point3f& p3,
                 double focalPx, double baselineM, float faceWidthPx) {
  const int x = cvRound(p2.x), y = cvRound(p2.y), r = cvRound(0.3f * faceWidthPx);
  if (!(p3.z > 0) || x < r || y < r || x >= truth.disparity.cols - r ||
      y >= truth.disparity.rows - r)
    return false;
  const double d = truth.disparity.at<std::int16_t>(y, x) / 16.0;
  if (!(d > 0)) return false;
  return focalPx * baselineM / d > p3.z - 0.1;
}

bool near(cv::Point2f a, cv::Point2f b, double tolerance) {
  return std::hypot(double(a.x - b.x), double(a.y - b.y)) <= tolerance;
}

double tolerancePx(const synth::PersonTruth& p) {
  return std::max(20.0, 0.5 * p.faceWidthPx);
}

// Scores one finished frame into `r`; returns whether it is a loss frame.
class Scorer {
 public:
  Scorer(const TrialOptions& o, double focalPx, double baselineM, TrialResult& r)
      : election_(o.tracker.election), focal_(focalPx), baseline_(baselineM), r_(r) {}

  bool score(const Frame& f, const synth::FrameTruth& truth, bool& truthGodfather,
             bool (&partLost)[3]) {
    ++r_.frames;
    countDetections(f, truth);
    const synth::PersonTruth& main = truth.people.at(0);
    std::optional<bool> seen;
    if (main.visible) seen = main.insideZone;
    truthGodfather = election_.update(truth.timeS, seen) == ElectionState::Godfather;
    if (!truthGodfather) return false;
    ++r_.godfatherFrames;
    const double tol = tolerancePx(main);
    const BodySample& b = f.body;
    bool lost = false;
    auto part = [&](bool visible, const PartState& track, cv::Point2f at, PartScore& score,
                    bool& partIsLost) {
      if (!visible) return;
      ++score.visible;
      if (!b.godfather || !track.tracked || !near(track.image, at, tol)) {
        ++score.lost;
        lost = partIsLost = true;
      }
    };
    part(main.visible, b.head, main.head2d, r_.head, partLost[0]);
    part(handVisible(truth, main.leftHand2d, main.leftHand3d, focal_, baseline_, main.faceWidthPx),
         b.leftHand, main.leftHand2d, r_.leftHand, partLost[1]);
    part(
        handVisible(truth, main.rightHand2d, main.rightHand3d, focal_, baseline_, main.faceWidthPx),
        b.rightHand, main.rightHand2d, r_.rightHand, partLost[2]);
    if (lost) ++r_.lostFrames;
    return lost;
  }

 private:
  void countDetections(const Frame& f, const synth::FrameTruth& truth) {
    if (!f.detections) return;
    auto isPart = [&](cv::Point2f at, bool face) {
      for (const synth::PersonTruth& p : truth.people) {
        if (!p.visible || !p.insideZone) continue;
        const double tol = tolerancePx(p);
        if (face ? near(at, p.head2d, tol)
                 : (near(at, p.leftHand2d, tol) || near(at, p.rightHand2d, tol)))
          return true;
      }
      return false;
    };
    for (const FaceDetection& d : f.detections->faces) {
      ++r_.detections;
      if (!isPart(d.centre, true)) ++r_.falseDetections;
    }
    for (const HandDetection& d : f.detections->hands) {
      ++r_.detections;
      if (!isPart(d.centroid, false)) ++r_.falseDetections;
    }
  }

  GodfatherElection election_;
  double focal_, baseline_;
  TrialResult& r_;
};

}  // namespace

TrialResult runTrackingTrial(const TrialOptions& o, DetectionScope scope,
                             std::vector<std::unique_ptr<Stage>> extraStages,
                             TrialFrameCallback onFrame) {
  if (o.frames < 1)
    throw Error("a tracking trial needs at least 1 frame, got " + std::to_string(o.frames));
  PipelineConfig c;
  c.maxFrames = o.frames;
  c.inFlight = o.inFlight;
  c.stereo = o.stereo;
  c.median = o.median;
  c.zoneSearch = o.zoneSearch;
  c.backend = o.backend;
  c.threads = o.threads;
  c.detection = scope;
  c.detector = o.detector;
  c.tracker = o.tracker;
  c.headControl = o.headControl;
  c.head = o.head;
  c.followHeadTurns = o.followHeadTurns;

  TrialResult result;
  result.seed = o.seed;
  result.scope = scope;
  std::unique_ptr<Scorer> scorer;
  const synth::SyntheticScene* scene = nullptr;
  PipelineHooks hooks;
  hooks.onFrame = [&](const Frame& f) {
    const synth::FrameTruth* truth = sim::truthOf(f);
    if (!truth) throw Error("a synthetic frame without its truth");
    bool truthGodfather = false;
    bool partLost[3] = {false, false, false};
    const bool lost = scorer->score(f, *truth, truthGodfather, partLost);
    if (onFrame)
      onFrame(TrialFrame{f,
                         *truth,
                         truthGodfather,
                         lost,
                         {partLost[0], partLost[1], partLost[2]},
                         scene->focalPx(),
                         scene->baselineM()});
  };
  hooks.extraStages = std::move(extraStages);
  hooks.openSource = sim::syntheticSourceOpener({trialScene(o), o.frames}, &scene);
  AssembledPipeline pipeline = buildPipeline(c, std::move(hooks));
  scorer = std::make_unique<Scorer>(o, scene->focalPx(), scene->baselineM(), result);
  result.summary = pipeline.run();
  return result;
}

}  // namespace horopter
