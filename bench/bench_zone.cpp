// frontend/<backend>/640x480/d64/w9/t<n>/scene, .../zone and .../zone_guard:
// the whole front end (as the frontend/ rows) on a frame of the synthetic
// scene at its default rig and fixation, with the thresholds `horopter run`
// computes: over the full range (scene), zone-limited (zone: each frame
// searches zoneSearchRange() of those thresholds, `run --zone-search 1
// --zone-guard-step 0`) and zone-limited with the guard below the range at
// its default step (zone_guard, `run --zone-search 1`). The ratios to scene
// are what zone-limited matching saves; `horopter eval-zone` measures what
// it changes in the mask.
#include <algorithm>
#include <span>

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

enum class Search { Full, Zone, ZoneGuard };

void runSceneFrontend(benchmark::State& state, const Backend& backend, int threads, Search mode) {
  const SceneFrame& f = sceneFrame();
  const StereoParams params;  // 64 disparities, block 9: what `horopter run` uses
  ZoneSearch search;          // the guard at its default step
  search.enabled = mode != Search::Full ? 1 : 0;
  if (mode == Search::Zone) search.guardStep = 0;
  const SearchRange range = zoneSearchRange(params, f.thresholds, search);
  StereoFrontend frontend(params, MedianParams{}, backend, threads);
  for (auto _ : state) {
    frontend.computeDisparity(viewOf(f.left), viewOf(f.right), range);
    frontend.computeMask(f.thresholds, viewOf(f.leftColour));
  }
  state.counters["disparities"] = range.numDisparities;
  state.counters["guard_checked"] =
      range.guardStep > 0 ? (range.minDisparity - params.minDisparity) / range.guardStep : 0;
  if (mode != Search::Full) {
    // What per-column search bottoms would search (not implemented: a
    // figure for the speed goal): the mean over 128-pixel tiles (the AVX2
    // matcher's) and over single columns of the range zoneSearchRange()
    // gives for their thresholds alone.
    const std::span<const std::int16_t> all(f.thresholds);
    double tiles = 0, columns = 0;
    int tileCount = 0;
    for (std::size_t x = 0; x < all.size(); x += 128, ++tileCount)
      tiles += zoneSearchRange(params, all.subspan(x, std::min<std::size_t>(128, all.size() - x)),
                               search)
                   .numDisparities;
    for (std::size_t x = 0; x < all.size(); ++x)
      columns += zoneSearchRange(params, all.subspan(x, 1), search).numDisparities;
    state.counters["tile_disparities"] = tiles / tileCount;
    state.counters["column_disparities"] = columns / static_cast<double>(all.size());
  }
  setPixelCounters(state, FrameSize{f.left.cols, f.left.rows});
}

}  // namespace

void registerZoneRows() {
  for (const Backend* backend : availableBackends()) {
    if (backend->name.rfind("opencl", 0) == 0) continue;  // the CPU front end's rows
    for (const int threads : kThreadCounts) {
      for (const Search mode : {Search::Full, Search::Zone, Search::ZoneGuard}) {
        const char* suffix = mode == Search::Full   ? "/scene"
                             : mode == Search::Zone ? "/zone"
                                                    : "/zone_guard";
        const std::string name =
            "frontend/" + backend->name + "/640x480/d64/w9/t" + std::to_string(threads) + suffix;
        auto* row = measure(benchmark::RegisterBenchmark(
            name.c_str(), [backend, threads, mode](benchmark::State& state) {
              runSceneFrontend(state, *backend, threads, mode);
            }));
        if (threads > 1) row->UseRealTime();
      }
    }
  }
}

}  // namespace horopter::bench
