// The C API's whole pipeline: horopter_run over buildPipeline, the builder
// `horopter run` and the Python module use (include/horopter/horopter.h).
#include <atomic>
#include <cmath>
#include <string>

#include "guarded.hpp"
#include "horopter/app/pipeline_builder.hpp"
#include "horopter/horopter.h"

using namespace horopter::c_api;

namespace {

std::string textOr(const char* text, const char* fallback) {
  return text ? std::string(text) : std::string(fallback);
}

horopter::PipelineConfig configOf(const horopter_run_config& r) {
  horopter::PipelineConfig c;
  if (!r.source) throw InvalidArgument("config.source is NULL: give dir:PATH, video:L,R, ...");
  c.source = r.source;
  if (r.frames < 0)
    throw InvalidArgument("frames must be >= 0 (0: the source's end), got " +
                          std::to_string(r.frames));
  if (r.frames > 0) c.maxFrames = r.frames;
  if (r.width < 0 || r.height < 0 || r.width > 16384 || r.height > 16384)
    throw InvalidArgument("width and height must be 0..16384 (0: the camera's), got " +
                          std::to_string(r.width) + "x" + std::to_string(r.height));
  c.capture.width = r.width;
  c.capture.height = r.height;
  c.backend = textOr(r.backend, "auto");
  if (r.threads < 1 || r.threads > 256)
    throw InvalidArgument("threads must be 1..256, got " + std::to_string(r.threads));
  c.threads = r.threads;
  c.inFlight = r.in_flight;  // the pipeline checks 1..64
  c.live = r.live != 0;
  const std::string detect = textOr(r.detect, "region");
  if (detect == "region")
    c.detection = horopter::DetectionScope::HoropterRegion;
  else if (detect == "full")
    c.detection = horopter::DetectionScope::FullImage;
  else if (detect == "off")
    c.detection.reset();
  else
    throw InvalidArgument("detect takes \"region\", \"full\" or \"off\", got \"" + detect + "\"");
  paramsOf(r.stereo, c.stereo, c.median);
  for (const double v : {r.fixation_disparity_px, r.focal_px})
    if (!(v >= 0 && std::isfinite(v)))
      throw InvalidArgument("fixation_disparity_px and focal_px must be >= 0 (0: the default)");
  if (r.fixation_disparity_px > 0) c.zone.fixationDisparityPx = r.fixation_disparity_px;
  if (r.focal_px > 0) c.zone.focalPx = r.focal_px;
  return c;
}

horopter_image viewOf(const cv::Mat& m, horopter_pixel_type type) {
  if (m.empty()) return {nullptr, 0, 0, 0, type};
  return {m.data, m.cols, m.rows, static_cast<ptrdiff_t>(m.step[0]), type};
}

horopter_part partOf(const horopter::PartState& p) {
  return {p.tracked ? 1 : 0, p.image.x, p.image.y};
}

}  // namespace

extern "C" {

void horopter_run_config_default(horopter_run_config* config) {
  if (!config) return;
  *config = horopter_run_config{};
  config->source = NULL;
  config->frames = 0;
  config->width = 0;
  config->height = 0;
  config->backend = "auto";
  config->threads = 1;
  config->in_flight = 3;
  config->live = 0;
  config->detect = "region";
  horopter_stereo_params_default(&config->stereo);
  config->stereo.left_band = horopter::runStereoDefaults().leftBand;  // the run's own
  config->fixation_disparity_px = 0;
  config->focal_px = 0;
}

horopter_status horopter_run(const horopter_run_config* config, horopter_frame_callback on_frame,
                             void* user, horopter_run_summary* summary) {
  return guarded([&] {
    requireNonNull(config, "config");
    const horopter::PipelineConfig c = configOf(*config);
    std::atomic<bool> stop{false};
    std::uint64_t digest = 0;
    horopter::PipelineHooks hooks;
    hooks.stopRequested = &stop;
    hooks.onFrame = [&](const horopter::Frame& f) {
      digest = horopter::foldDigest(digest, horopter::frameDigest(f));
      if (!on_frame) return;
      horopter_frame_result r{};
      r.index = f.index;
      r.godfather = f.body.godfather ? 1 : 0;
      r.head = partOf(f.body.head);
      r.left_hand = partOf(f.body.leftHand);
      r.right_hand = partOf(f.body.rightHand);
      r.disparity = viewOf(f.disparity, HOROPTER_S16C1);
      r.mask = viewOf(f.mask, HOROPTER_U8C1);
      if (on_frame(&r, user) != 0) stop = true;
    };
    horopter::AssembledPipeline pipeline = horopter::buildPipeline(c, std::move(hooks));
    const horopter::RunSummary s = pipeline.run();
    if (summary) *summary = {s.completed, s.seconds, s.fps(), digest};
  });
}

}  // extern "C"
