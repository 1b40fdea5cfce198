// One row per kernel. Each kernel runs on the output of the stages before
// it, computed once outside the timed loop with the scalar reference (every
// backend gives its result bit for bit):
//   prefilter/      x-Sobel of the left view, filtered and texture outputs
//   sad/            matchBlocks on the prefiltered pair
//   lr_check/       leftRightCheck on matchBlocks' output
//   speckle/        filterSpeckles (window 100, range 32) on the checked map
//   median/         medianFilter (k3, k5) on the speckle-filtered map
//   horopter_mask/  horopterMask of the median output, segmenting the BGR left view
// The maps of the later stages come from the d64/w9 search.
#include <map>
#include <tuple>
#include <vector>

#include "bench_inputs.hpp"
#include "bench_support.hpp"
#include "horopter/kernels/kernels.hpp"
#include "registration.hpp"

namespace horopter::bench {

namespace {

// Kernel rows call one kernel, whole frame, on the calling thread.
constexpr int kKernelThreads = 1;

constexpr int kCleanupDisparities = 64;
constexpr int kMedianSizes[] = {3, 5};

// The intermediate images of the front end for one setting.
struct Stages {
  Image leftFiltered, rightFiltered, texture;  // prefilter
  Image matched, winnerRight;                  // matchBlocks
  Image checked;                               // leftRightCheck
  Image cleaned;                               // filterSpeckles
  Image median;                                // medianFilter, k5
};

Stages computeStages(const MatchSetting& setting) {
  const StereoPair& pair = stereoPair(setting.size);
  const StereoParams params = frontendParams(setting);
  const auto bytes = [&] {
    return Image(setting.size.width, setting.size.height, PixelType::U8C1);
  };
  const auto shorts = [&] {
    return Image(setting.size.width, setting.size.height, PixelType::S16C1);
  };
  Stages s{bytes(), bytes(), bytes(), shorts(), shorts(), shorts(), shorts(), shorts()};
  prefilterXSobel(pair.left.view(), params.preFilterCap, s.leftFiltered.view(), s.texture.view());
  prefilterXSobel(pair.right.view(), params.preFilterCap, s.rightFiltered.view(), {});
  matchBlocks(s.leftFiltered.view(), s.rightFiltered.view(), s.texture.view(), params,
              s.matched.view(), s.winnerRight.view());
  copyPixels(s.matched, s.checked);
  leftRightCheck(s.checked.view(), s.winnerRight.view(), params);
  copyPixels(s.checked, s.cleaned);
  filterSpeckles(s.cleaned.view(), params);
  medianFilter(s.cleaned.view(), s.median.view(), MedianParams{}, invalidDisparity(params));
  return s;
}

// The stages of this setting, computed on first use and kept for the run.
const Stages& stages(const MatchSetting& setting) {
  static std::map<std::tuple<int, int, int, int>, Stages> cache;
  const auto key = std::make_tuple(setting.size.width, setting.size.height, setting.numDisparities,
                                   setting.blockSize);
  auto it = cache.find(key);
  if (it == cache.end()) it = cache.emplace(key, computeStages(setting)).first;
  return it->second;
}

MatchSetting cleanupSetting(FrameSize size) {
  return {size, kCleanupDisparities, kBlockSize};
}

void runPrefilter(benchmark::State& state, const Backend& backend, FrameSize size) {
  const StereoPair& pair = stereoPair(size);
  const int cap = StereoParams{}.preFilterCap;
  Image filtered(size.width, size.height, PixelType::U8C1);
  Image texture(size.width, size.height, PixelType::U8C1);
  for (auto _ : state)
    prefilterXSobel(pair.left.view(), cap, filtered.view(), texture.view(), backend);
  setPixelCounters(state, size);
}

void runSad(benchmark::State& state, const Backend& backend, const MatchSetting& setting) {
  const Stages& s = stages(setting);
  const StereoParams params = frontendParams(setting);
  Image disparity(setting.size.width, setting.size.height, PixelType::S16C1);
  Image winnerRight(setting.size.width, setting.size.height, PixelType::S16C1);
  for (auto _ : state) {
    matchBlocks(s.leftFiltered.view(), s.rightFiltered.view(), s.texture.view(), params,
                disparity.view(), winnerRight.view(), backend);
  }
  setPixelCounters(state, setting);
}

void runLeftRightCheck(benchmark::State& state, const Backend& backend,
                       const MatchSetting& setting) {
  const Stages& s = stages(setting);
  const StereoParams params = frontendParams(setting);
  Image disparity(setting.size.width, setting.size.height, PixelType::S16C1);
  for (auto _ : state) {
    // In place: every run starts from matchBlocks' output.
    state.PauseTiming();
    copyPixels(s.matched, disparity);
    state.ResumeTiming();
    leftRightCheck(disparity.view(), s.winnerRight.view(), params, backend);
  }
  setPixelCounters(state, setting.size);
}

void runSpeckle(benchmark::State& state, const Backend& backend, FrameSize size) {
  const MatchSetting setting = cleanupSetting(size);
  const Stages& s = stages(setting);
  const StereoParams params = frontendParams(setting);
  Image disparity(size.width, size.height, PixelType::S16C1);
  for (auto _ : state) {
    // In place: every run starts from the checked map.
    state.PauseTiming();
    copyPixels(s.checked, disparity);
    state.ResumeTiming();
    filterSpeckles(disparity.view(), params, backend);
  }
  setPixelCounters(state, size);
}

void runMedian(benchmark::State& state, const Backend& backend, FrameSize size, int kernelSize) {
  const MatchSetting setting = cleanupSetting(size);
  const Stages& s = stages(setting);
  const std::int16_t invalid = invalidDisparity(frontendParams(setting));
  MedianParams median;
  median.kernelSize = kernelSize;
  Image out(size.width, size.height, PixelType::S16C1);
  for (auto _ : state)
    medianFilter(s.cleaned.view(), out.view(), median, invalid, backend);
  setPixelCounters(state, size);
}

void runHoropterMask(benchmark::State& state, const Backend& backend, FrameSize size) {
  const MatchSetting setting = cleanupSetting(size);
  const Stages& s = stages(setting);
  const StereoPair& pair = stereoPair(size);
  const std::int16_t invalid = invalidDisparity(frontendParams(setting));
  const std::vector<std::int16_t> thresholds = sceneThresholds(size);
  Image mask(size.width, size.height, PixelType::U8C1);
  Image segmented(size.width, size.height, PixelType::U8C3);
  for (auto _ : state) {
    horopterMask(s.median.view(), thresholds, invalid, mask.view(), pair.leftColour.view(),
                 segmented.view(), backend);
  }
  setPixelCounters(state, size);
}

// Registers one row under `name`; `run` takes the benchmark state.
template <typename Run>
void addRow(const std::string& name, Run run) {
  measure(benchmark::RegisterBenchmark(name.c_str(), run));
}

}  // namespace

void registerKernelRows() {
  for (const Backend* backend : availableBackends()) {
    const Backend& b = *backend;
    const std::string tail = "/" + b.name + "/";  // "/scalar/"
    for (const FrameSize size : kSizes) {
      addRow("prefilter" + tail + sizeTag(size),
             [&b, size](benchmark::State& state) { runPrefilter(state, b, size); });
    }
    for (const MatchSetting& setting : matchSettings(/*withTarget=*/false)) {
      const std::string point = sizeTag(setting.size) + "/" + matchTag(setting, kKernelThreads);
      addRow("sad" + tail + point,
             [&b, setting](benchmark::State& state) { runSad(state, b, setting); });
    }
    for (const MatchSetting& setting : matchSettings(/*withTarget=*/false)) {
      const std::string point = sizeTag(setting.size) + "/" + matchTag(setting, kKernelThreads);
      addRow("lr_check" + tail + point,
             [&b, setting](benchmark::State& state) { runLeftRightCheck(state, b, setting); });
    }
    for (const FrameSize size : kSizes) {
      addRow("speckle" + tail + sizeTag(size),
             [&b, size](benchmark::State& state) { runSpeckle(state, b, size); });
    }
    for (const FrameSize size : kSizes) {
      for (const int k : kMedianSizes) {
        addRow("median" + tail + sizeTag(size) + "/k" + std::to_string(k),
               [&b, size, k](benchmark::State& state) { runMedian(state, b, size, k); });
      }
    }
    for (const FrameSize size : kSizes) {
      addRow("horopter_mask" + tail + sizeTag(size),
             [&b, size](benchmark::State& state) { runHoropterMask(state, b, size); });
    }
  }
}

}  // namespace horopter::bench
