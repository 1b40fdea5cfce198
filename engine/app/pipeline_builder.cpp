// buildPipeline: the frame pipeline from one configuration; see
// horopter/app/pipeline_builder.hpp.
#include "horopter/app/pipeline_builder.hpp"

#include <algorithm>
#include <utility>

#include "horopter/app/interaction_stages.hpp"
#include "horopter/core/error.hpp"
#include "horopter/movement/movement.hpp"
#include "horopter/vision/calibration.hpp"
#include "horopter/vision/geometry.hpp"

namespace horopter {

StereoParams runStereoDefaults() {
  StereoParams p;
  p.leftBand = 16;
  return p;
}

namespace {

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

ZoneSetup zoneSetup(const PipelineConfig& c, OpenedSource& opened) {
  if (!c.zone.calib.empty()) return calibratedZone(c.zone);
  ZoneSetup setup;
  if (opened.thresholds) {
    setup.thresholds = std::move(opened.thresholds);
    setup.rig = opened.rig;
    if (opened.framesPerSecond > 0) setup.framesPerSecond = opened.framesPerSecond;
  } else {
    setup.thresholds =
        fixationDisparityThresholds(c.stereo, c.zone.fixationDisparityPx, c.zone.focalPx);
  }
  return setup;
}

}  // namespace

struct AssembledPipeline::Parts {
  std::unique_ptr<FrameSource> source;
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
bool AssembledPipeline::closedLoop() const {
  return parts_->closedLoop;
}
bool AssembledPipeline::detecting() const {
  return parts_->detecting;
}

AssembledPipeline buildPipeline(const PipelineConfig& c, PipelineHooks hooks) {
  validate(c.zoneSearch, c.stereo);
  auto parts = std::make_unique<AssembledPipeline::Parts>();
  parts->backend = &findBackend(c.backend);
  parts->detecting = c.detection.has_value() && c.stopAfter == StopAfter::Everything;

  // Capture: the caller's opener first (the simulator's sources), then the
  // library's. A steerable source is wanted for the closed loop.
  const bool steerable = parts->detecting && c.headControl && !c.live && c.zone.calib.empty();
  std::optional<OpenedSource> opened;
  if (hooks.openSource) opened = hooks.openSource(c, steerable);
  if (!opened) {
    opened.emplace();
    opened->source = frameSourceOf(openSource(c.source, c.capture));
  }
  if (!opened->source) throw Error("the source opener for '" + c.source + "' opened nothing");
  parts->closedLoop = steerable && opened->headControl;
  const ZoneSetup zone = zoneSetup(c, *opened);
  parts->source = std::move(opened->source);

  PipelineOptions options;
  options.mode = c.live ? PipelineMode::Live : PipelineMode::Offline;
  options.inFlight = c.inFlight;
  options.maxFrames = c.maxFrames;
  options.stopRequested = hooks.stopRequested;
  options.onFrame = std::move(hooks.onFrame);
  parts->pipeline = std::make_unique<Pipeline>(options);
  Pipeline& p = *parts->pipeline;

  if (c.stopAfter == StopAfter::Rectify) {
    p.add(makeRectifyStage(zone.rectify));
  } else {
    p.add(makeRectifyStage(zone.rectify, zone.thresholds));
    p.add(makeDisparityStage(c.stereo, c.median, *parts->backend, c.threads, c.zoneSearch));
    if (c.stopAfter != StopAfter::Disparity) p.add(makeMaskStage(c.stereo, *parts->backend));
  }
  if (parts->detecting) {
    DetectorOptions detector = c.detector;
    detector.scope = *c.detection;
    p.add(makeDetectionStage(detector));
    TrackerOptions tracker = c.tracker;
    tracker.rig = zone.rig;
    tracker.framesPerSecond = zone.framesPerSecond;
    tracker.maxDisparityPx = largestDisparity(c.stereo, c.zoneSearch);
    tracker.captureTime = c.live;
    if (parts->closedLoop && c.followHeadTurns) tracker.capturePose = opened->capturePose;
    p.add(makeTrackingStage(tracker));
    if (parts->closedLoop) p.add(opened->headControl(c.head));
    if (c.movement) p.add(makeMovementStage(c.movement));
  }
  for (auto& stage : hooks.extraStages)
    p.add(std::move(stage));
  return AssembledPipeline(std::move(parts));
}

}  // namespace horopter
