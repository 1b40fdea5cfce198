// frontend/<backend>/640x480/d64/w9/t<n>/scene and .../zone: the whole front
// end (as the frontend/ rows) on a frame of the synthetic scene at its
// default rig and fixation, with the thresholds `horopter run` computes:
// over the full range (scene) and zone-limited (zone: each frame searches
// zoneSearchRange() of those thresholds, `run --zone-search 1`). The ratio
// of the two is what zone-limited matching saves; `horopter eval-zone`
// measures what it changes in the mask.
#include <opencv2/imgproc.hpp>

#include "bench_support.hpp"
#include "horopter/sim/synthetic_scene.hpp"
#include "horopter/vision/frontend.hpp"
#include "horopter/vision/geometry.hpp"
#include "horopter/vision/opencv.hpp"
#include "horopter/vision/zone_search.hpp"
#include "registration.hpp"

namespace horopter::bench {

namespace {

struct SceneFrame {
  cv::Mat left, right, leftColour;
  std::vector<std::int16_t> thresholds;
};

// Frame 150 of the default run (the person inside the zone, the
// distractor outside), made once.
const SceneFrame& sceneFrame() {
  static const SceneFrame frame = [] {
    synth::SyntheticScene scene{synth::SceneOptions{}};
    const synth::SyntheticFrame f = scene.render(150);
    SceneFrame out;
    out.leftColour = f.left;
    cv::cvtColor(f.left, out.left, cv::COLOR_BGR2GRAY);
    cv::cvtColor(f.right, out.right, cv::COLOR_BGR2GRAY);
    RectifiedGeometry g;
    g.focalPx = scene.focalPx();
    g.cx = scene.cx();
    g.cy = scene.cy();
    g.baseline = scene.baselineM();
    out.thresholds = std::vector<std::int16_t>(static_cast<std::size_t>(f.left.cols), 1);
    horopterThresholds(
        g, viethMuellerCircle(g.baseline, fixationFromVergence(g.baseline, f.truth.head.vergence)),
        out.thresholds);
    return out;
  }();
  return frame;
}

void runSceneFrontend(benchmark::State& state, const Backend& backend, int threads, bool zone) {
  const SceneFrame& f = sceneFrame();
  const StereoParams params;  // 64 disparities, block 9: what `horopter run` uses
  ZoneSearch search;
  search.enabled = zone ? 1 : 0;
  const SearchRange range = zoneSearchRange(params, f.thresholds, search);
  StereoFrontend frontend(params, MedianParams{}, backend, threads);
  for (auto _ : state) {
    frontend.computeDisparity(viewOf(f.left), viewOf(f.right), range);
    frontend.computeMask(f.thresholds, viewOf(f.leftColour));
  }
  state.counters["disparities"] = range.numDisparities;
  setPixelCounters(state, FrameSize{f.left.cols, f.left.rows});
}

}  // namespace

void registerZoneRows() {
  for (const Backend* backend : availableBackends()) {
    if (backend->name.rfind("opencl", 0) == 0) continue;  // the CPU front end's rows
    for (const int threads : kThreadCounts) {
      for (const bool zone : {false, true}) {
        const std::string name = "frontend/" + backend->name + "/640x480/d64/w9/t" +
                                 std::to_string(threads) + (zone ? "/zone" : "/scene");
        auto* row = measure(benchmark::RegisterBenchmark(
            name.c_str(), [backend, threads, zone](benchmark::State& state) {
              runSceneFrontend(state, *backend, threads, zone);
            }));
        if (threads > 1) row->UseRealTime();
      }
    }
  }
}

}  // namespace horopter::bench
