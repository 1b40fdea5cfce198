// pipeline/...: the front end (rectify, disparity, mask) through the
// scheduler at 640x480, with 1 and with 3 frames in flight, so the gain of
// overlapping frames is measured in one run:
//   pipeline/replay/inflight:K     frames pre-rendered by the synthetic scene,
//                                  replayed (the scheduler and the kernels)
//   pipeline/synthetic/inflight:K  the synthetic scene rendering every frame
// One iteration is a batch of 30 frames; frames/s counts frames.
#include <benchmark/benchmark.h>

#include "horopter/app/frame.hpp"
#include "horopter/app/vision_stages.hpp"
#include "horopter/kernels/backend.hpp"
#include "horopter/sim/synthetic_source.hpp"
#include "horopter/vision/capture.hpp"

namespace {

using namespace horopter;

constexpr int kBatch = 30;

// Replays a few rendered frames, as fast as the pipeline takes them.
class ReplaySource : public FrameSource {
 public:
  explicit ReplaySource(const std::vector<Frame>& frames) : frames_(frames) {}
  std::string name() const override { return "replay"; }
  bool next(Frame& f) override {
    if (served_ == kBatch) return false;
    const Frame& src = frames_[static_cast<std::size_t>(served_++) % frames_.size()];
    f.left = src.left;
    f.right = src.right;
    return true;
  }

 private:
  const std::vector<Frame>& frames_;
  int served_ = 0;
};

const std::vector<Frame>& replayFrames() {
  static const std::vector<Frame> frames = [] {
    sim::SyntheticSource source(synth::SceneOptions{}, 8);
    std::vector<Frame> out(8);
    for (auto& f : out)
      source.next(f);
    return out;
  }();
  return frames;
}

void addFrontEnd(Pipeline& pipeline, int threads) {
  const StereoParams stereo;
  const Backend& backend = findBackend("auto");
  pipeline
      .add(makeRectifyStage({},
                            [](const Frame& f, std::vector<std::int16_t>& out) {
                              out.assign(f.leftGrey.cols, 16 * 20);
                            }))
      .add(makeDisparityStage(stereo, MedianParams{}, backend, threads))
      .add(makeMaskStage(stereo, backend));
}

void runBatches(benchmark::State& state, bool render) {
  const int inFlight = static_cast<int>(state.range(0));
  const int threads = 2;
  PipelineOptions options;
  options.inFlight = inFlight;
  options.maxFrames = kBatch;
  Pipeline pipeline(options);
  addFrontEnd(pipeline, threads);
  replayFrames();  // rendered once, outside the timing
  std::unique_ptr<sim::SyntheticSource> synthetic;
  if (render) {
    // As horopter run: with frames in flight the scene renders on the
    // capture thread alone, the other core busy with the frames ahead.
    synth::SceneOptions scene;
    if (inFlight > 1) scene.threads = 1;
    synthetic = std::make_unique<sim::SyntheticSource>(scene, 1 << 30);
  }
  for (auto _ : state) {
    if (render) {
      pipeline.run(*synthetic);
    } else {
      ReplaySource replay(replayFrames());
      pipeline.run(replay);
    }
  }
  state.counters["frames/s"] = benchmark::Counter(static_cast<double>(state.iterations()) * kBatch,
                                                  benchmark::Counter::kIsRate);
}

}  // namespace

BENCHMARK_CAPTURE(runBatches, replay, false)
    ->Name("pipeline/replay/640x480/t2")
    ->ArgName("inflight")
    ->Arg(1)
    ->Arg(3)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(runBatches, synthetic, true)
    ->Name("pipeline/synthetic/640x480/t2")
    ->ArgName("inflight")
    ->Arg(1)
    ->Arg(3)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
