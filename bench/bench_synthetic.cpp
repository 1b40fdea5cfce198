// synthetic/...: the built-in synthetic stereo scene rendering frames at
// 640x480 (both views and the whole ground truth):
//   still_head    frames 60, 61, ... with the head still (the room comes from
//                 its cache; each frame redraws where the people moved)
//   moving_head   the head turning every frame (the room is rendered again)
//   run/t1, run/t2  frames 0-299 in a loop, as `horopter run` renders them
//                 (the walk in, then the movements), on 1 and 2 OpenCV threads:
//                 t1 is the renderer's CPU time per frame
// Registered at static initialisation: the rows do not depend on the backends.
#include <benchmark/benchmark.h>

#include <cmath>
#include <opencv2/core/utility.hpp>

#include "horopter/sim/synthetic_scene.hpp"

namespace {

void renderFrames(benchmark::State& state, bool moveHead) {
  horopter::synth::SyntheticScene scene{horopter::synth::SceneOptions{}};
  scene.render(0);  // loads the textures, fills the cache
  int index = 60;
  for (auto _ : state) {
    if (moveHead) scene.commandHead({0.05 * std::sin(0.1 * index), 0.0, 0.06});
    benchmark::DoNotOptimize(scene.render(index++));
  }
  state.counters["frames/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

// The frames of a default `horopter run`, over and over, on `threads`
// OpenCV threads (restored afterwards).
void renderRun(benchmark::State& state) {
  const int previous = cv::getNumThreads();
  cv::setNumThreads(static_cast<int>(state.range(0)));
  {
    horopter::synth::SyntheticScene scene{horopter::synth::SceneOptions{}};
    scene.render(299);  // loads the textures, fills the cache
    int index = 0;
    for (auto _ : state) {
      benchmark::DoNotOptimize(scene.render(index));
      index = (index + 1) % 300;
    }
  }
  cv::setNumThreads(previous);
  state.counters["frames/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

}  // namespace

BENCHMARK(renderRun)
    ->Name("synthetic/640x480/run")
    ->ArgName("t")
    ->Arg(1)
    ->Arg(2)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(renderFrames, still_head, false)
    ->Name("synthetic/640x480/still_head")
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(renderFrames, moving_head, true)
    ->Name("synthetic/640x480/moving_head")
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
