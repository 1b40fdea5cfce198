// The synthetic scene as a pipeline source; see horopter/sim/synthetic_source.hpp.
#include "horopter/sim/synthetic_source.hpp"

#include <algorithm>

#include "horopter/core/error.hpp"
#include "horopter/sim/closed_loop.hpp"
#include "horopter/vision/geometry.hpp"

namespace horopter::sim {

SyntheticSource::SyntheticSource(const synth::SceneOptions& options, int frames)
    : scene_(options), frames_(frames) {
  if (frames < 1)
    throw Error("the synthetic scene needs at least 1 frame, got " + std::to_string(frames));
}

bool SyntheticSource::next(Frame& frame) {
  if (next_ >= frames_) return false;
  synth::SyntheticFrame rendered = scene_.render(next_++);
  frame.left = std::move(rendered.left);
  frame.right = std::move(rendered.right);
  // A plain Frame (not from newFrame()) gets the images only.
  if (auto* sim = dynamic_cast<SimFrame*>(&frame)) sim->truth = std::move(rendered.truth);
  return true;
}

ThresholdFunction syntheticZoneThresholds(const synth::SyntheticScene& scene) {
  RectifiedGeometry g;
  g.focalPx = scene.focalPx();
  g.cx = scene.cx();
  g.cy = scene.cy();
  g.baseline = scene.baselineM();
  return [g](const Frame& f, std::vector<std::int16_t>& out) {
    const synth::FrameTruth* truth = truthOf(f);
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

SourceOpener syntheticSourceOpener(SyntheticSourceOptions options,
                                   const synth::SyntheticScene** sceneOut) {
  return [options, sceneOut](const PipelineConfig& config,
                             bool steerable) -> std::optional<OpenedSource> {
    if (config.source != "synthetic") return std::nullopt;
    synth::SceneOptions sceneOptions = options.scene;
    // With frames in flight the other cores work on the frames ahead: the
    // scene renders on the capture thread alone rather than adding OpenCV's
    // threads beside the front end's pool (the frames do not depend on it).
    if (config.inFlight > 1) sceneOptions.threads = 1;
    OpenedSource opened;
    const synth::SyntheticScene* scene = nullptr;
    if (steerable) {
      auto s = std::make_unique<ClosedLoopSyntheticSource>(
          sceneOptions, options.frames, config.head.actuationDelayFrames, config.head.limits);
      ClosedLoopSyntheticSource* loop = s.get();
      scene = &s->scene();
      opened.headControl = [loop](const HeadControlOptions& head) {
        return makeSyntheticHeadControlStage(head, *loop);
      };
      opened.capturePose = syntheticCapturePose();
      opened.source = std::move(s);
    } else {
      auto s = std::make_unique<SyntheticSource>(sceneOptions, options.frames);
      scene = &s->scene();
      opened.source = std::move(s);
    }
    opened.thresholds = syntheticZoneThresholds(*scene);
    opened.rig = RectifiedGeometry{scene->focalPx(), scene->cx(), scene->baselineM(), scene->cy()};
    opened.framesPerSecond = scene->options().framesPerSecond;
    if (sceneOut) *sceneOut = scene;
    return opened;
  };
}

}  // namespace horopter::sim
