// buildPipeline: the frame pipeline from one configuration; see
// horopter/pipeline_builder.hpp.
#include "horopter/pipeline_builder.hpp"

#include <algorithm>
#include <any>
#include <utility>

#include "horopter/calibration.hpp"
#include "horopter/error.hpp"
#include "horopter/geometry.hpp"
#include "horopter/movement.hpp"
#include "horopter/synthetic_scene.hpp"

namespace horopter {

namespace {

// The zone's thresholds for each frame from the synthetic scene's rig and
// the vergence in the frame's truth (the head verges on what it looks at).
ThresholdFunction syntheticZoneThresholds(const synth::SyntheticScene& scene) {
  RectifiedGeometry g;
  g.focalPx = scene.focalPx();
  g.cx = scene.cx();
  g.cy = scene.cy();
  g.baseline = scene.baselineM();
  return [g](const Frame& f, std::vector<std::int16_t>& out) {
    const auto* truth = std::any_cast<synth::FrameTruth>(&f.truth);
    if (!truth) throw Error("a synthetic frame without its truth");
    if (!(truth->head.vergence > 1e-9)) {
      std::fill(out.begin(), out.end(), std::int16_t{1});  // fixation at infinity: all in front
      return;
    }
    const ViethMuellerCircle circle =
        viethMuellerCircle(g.baseline, fixationFromVergence(g.baseline, truth->head.vergence));
    horopterThresholds(g, circle, out);
  };
}

// Rectification, zone and rig: what the mask and the tracker need to know
// of the cameras.
struct ZoneSetup {
  RectifyFunction rectify;  // empty: the source is rectified already
  ThresholdFunction thresholds;
  RectifiedGeometry rig;        // focalPx 0: unknown (no 3-D points)
  double framesPerSecond = 30;  // the tracker's clock for recorded input
};

ZoneSetup calibratedZone(const ZoneOptions& zone) {
  if (!(zone.fixationDistanceM > 0 && std::isfinite(zone.fixationDistanceM)))
    throw Error("the fixation distance must be a positive number of metres");
  const StereoCalibration calibration = loadStereoCalibration(zone.calib);
  auto rectifier = std::make_shared<StereoRectifier>(calibration);
  ZoneSetup setup;
  setup.rectify = [rectifier](const cv::Mat& l, const cv::Mat& r, cv::Mat& lo, cv::Mat& ro) {
    rectifier->rectify(l, r);
    lo = rectifier->left().clone();  // the rectifier reuses its buffers
    ro = rectifier->right().clone();
  };
  const RectifiedGeometry g = rectifiedGeometry(calibration);
  setup.rig = g;
  const ViethMuellerCircle circle =
      viethMuellerCircle(g.baseline, fixationAtDistance(g.baseline, zone.fixationDistanceM));
  setup.thresholds = [g, circle](const Frame&, std::vector<std::int16_t>& out) {
    horopterThresholds(g, circle, out);
  };
  return setup;
}

ZoneSetup zoneSetup(const PipelineConfig& c, const synth::SyntheticScene* scene) {
  if (!c.zone.calib.empty()) return calibratedZone(c.zone);
  ZoneSetup setup;
  if (scene) {
    setup.thresholds = syntheticZoneThresholds(*scene);
    setup.rig = RectifiedGeometry{scene->focalPx(), scene->cx(), scene->baselineM(), scene->cy()};
    setup.framesPerSecond = scene->options().framesPerSecond;
  } else {
    setup.thresholds =
        fixationDisparityThresholds(c.stereo, c.zone.fixationDisparityPx, c.zone.focalPx);
  }
  return setup;
}

}  // namespace

struct AssembledPipeline::Parts {
  std::unique_ptr<FrameSource> source;
  const synth::SyntheticScene* scene = nullptr;
  bool closedLoop = false;
  bool detecting = false;
  const Backend* backend = nullptr;
  std::unique_ptr<Pipeline> pipeline;
};

AssembledPipeline::AssembledPipeline(std::unique_ptr<Parts> parts) : parts_(std::move(parts)) {}
AssembledPipeline::AssembledPipeline(AssembledPipeline&&) noexcept = default;
AssembledPipeline& AssembledPipeline::operator=(AssembledPipeline&&) noexcept = default;
AssembledPipeline::~AssembledPipeline() = default;

RunSummary AssembledPipeline::run() {
  return parts_->pipeline->run(*parts_->source);
}
FrameSource& AssembledPipeline::source() {
  return *parts_->source;
}
const Backend& AssembledPipeline::backend() const {
  return *parts_->backend;
}
const synth::SyntheticScene* AssembledPipeline::scene() const {
  return parts_->scene;
}
bool AssembledPipeline::closedLoop() const {
  return parts_->closedLoop;
}
bool AssembledPipeline::detecting() const {
  return parts_->detecting;
}

AssembledPipeline buildPipeline(const PipelineConfig& c, PipelineHooks hooks) {
  auto parts = std::make_unique<AssembledPipeline::Parts>();
  parts->backend = &findBackend(c.backend);
  parts->detecting = c.detection.has_value() && c.stopAfter == StopAfter::Everything;

  // Capture. With frames in flight the other cores work on the frames
  // ahead, so the synthetic scene renders on the capture thread alone rather
  // than adding OpenCV's threads beside the front end's pool.
  CaptureOptions capture = c.capture;
  if (c.inFlight > 1) capture.scene.threads = 1;
  parts->closedLoop = parts->detecting && c.headControl && !c.live && c.zone.calib.empty() &&
                      c.source == "synthetic";
  ClosedLoopSyntheticSource* loop = nullptr;
  if (parts->closedLoop) {
    auto s = std::make_unique<ClosedLoopSyntheticSource>(
        capture.scene, capture.frames, c.head.actuationDelayFrames, c.head.limits);
    loop = s.get();
    parts->scene = &s->scene();
    parts->source = std::move(s);
  } else {
    parts->source = openSource(c.source, capture);
    if (auto* synthetic = dynamic_cast<SyntheticSource*>(parts->source.get()))
      parts->scene = &synthetic->scene();
  }
  const ZoneSetup zone = zoneSetup(c, parts->scene);

  PipelineOptions options;
  options.mode = c.live ? PipelineMode::Live : PipelineMode::Offline;
  options.inFlight = c.inFlight;
  options.maxFrames = c.maxFrames;
  options.stopRequested = hooks.stopRequested;
  options.onFrame = std::move(hooks.onFrame);
  parts->pipeline = std::make_unique<Pipeline>(options);
  Pipeline& p = *parts->pipeline;

  p.add(makeRectifyStage(zone.rectify));
  if (c.stopAfter != StopAfter::Rectify) {
    p.add(makeDisparityStage(c.stereo, c.median, *parts->backend, c.threads));
    if (c.stopAfter != StopAfter::Disparity)
      p.add(makeMaskStage(zone.thresholds, c.stereo, *parts->backend));
  }
  if (parts->detecting) {
    DetectorOptions detector = c.detector;
    detector.scope = *c.detection;
    p.add(makeDetectionStage(detector));
    TrackerOptions tracker = c.tracker;
    tracker.rig = zone.rig;
    tracker.framesPerSecond = zone.framesPerSecond;
    tracker.maxDisparityPx = c.stereo.minDisparity + c.stereo.numDisparities - 1;
    tracker.captureTime = c.live;
    if (loop && c.followHeadTurns) tracker.capturePose = syntheticCapturePose();
    p.add(makeTrackingStage(tracker));
    if (loop) p.add(makeSyntheticHeadControlStage(c.head, *loop));
    if (c.movement) p.add(makeMovementStage(c.movement));
  }
  for (auto& stage : hooks.extraStages)
    p.add(std::move(stage));
  return AssembledPipeline(std::move(parts));
}

}  // namespace horopter
