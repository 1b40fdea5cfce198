// synthetic/...: the built-in synthetic stereo scene rendering frames at
// 640x480 (both views and the whole ground truth), with the head still (the
// room comes from the cache) and with the head turning every frame (the room
// is rendered again each time). Registered at static initialisation: the
// rows do not depend on the backends.
#include <benchmark/benchmark.h>

#include <cmath>

#include "horopter/synthetic_scene.hpp"

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

}  // namespace

BENCHMARK_CAPTURE(renderFrames, still_head, false)
    ->Name("synthetic/640x480/still_head")
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(renderFrames, moving_head, true)
    ->Name("synthetic/640x480/moving_head")
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
