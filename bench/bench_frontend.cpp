// frontend/<backend>/...: the whole per-frame chain as an application runs
// it: StereoFrontend::computeDisparity (prefilter, matching, left-right
// check, speckle filter, k5 median) then computeMask, segmenting the BGR left
// view. Default parameters at each setting, the 1280x720/d128/w15 target
// included (beside opencv_stereobm/1280x720/d128/w15 in bench_disparity).
#include "bench_inputs.hpp"
#include "bench_support.hpp"
#include "horopter/vision/frontend.hpp"
#include "registration.hpp"

namespace horopter::bench {

namespace {

void runFrontend(benchmark::State& state, const Backend& backend, const MatchSetting& setting,
                 int threads) {
  const StereoPair& pair = stereoPair(setting.size);
  const std::vector<std::int16_t> thresholds = sceneThresholds(setting.size);
  // The front end allocates its buffers in the first frame and reuses them;
  // with many iterations that first frame is amortised.
  StereoFrontend frontend(frontendParams(setting), MedianParams{}, backend, threads);
  for (auto _ : state) {
    frontend.computeDisparity(pair.left.view(), pair.right.view());
    frontend.computeMask(thresholds, pair.leftColour.view());
  }
  setPixelCounters(state, setting);
}

}  // namespace

void registerFrontendRows() {
  for (const MatchSetting& setting : matchSettings(/*withTarget=*/true)) {
    for (const Backend* backend : availableBackends()) {
      for (const int threads : kThreadCounts) {
        const std::string name = "frontend/" + backend->name + "/" + sizeTag(setting.size) + "/" +
                                 matchTag(setting, threads);
        auto* row = measure(benchmark::RegisterBenchmark(
            name.c_str(), [backend, setting, threads](benchmark::State& state) {
              runFrontend(state, *backend, setting, threads);
            }));
        if (threads > 1) row->UseRealTime();
      }
    }
  }
}

}  // namespace horopter::bench
