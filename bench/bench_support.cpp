#include "bench_support.hpp"

#include <cstring>

namespace horopter::bench {

namespace {

constexpr MatchSetting kTarget = {{1280, 720}, 128, 15};

}  // namespace

std::vector<MatchSetting> matchSettings(bool withTarget) {
  std::vector<MatchSetting> settings;
  for (const FrameSize size : kSizes) {
    for (const int numDisparities : kDisparityCounts)
      settings.push_back({size, numDisparities, kBlockSize});
  }
  if (withTarget) {
    settings.push_back(kTarget);
    settings.push_back({{640, 480}, 64, kBlockSize, PreFilterType::NormalizedResponse});
  }
  return settings;
}

std::vector<MatchSetting> bandSettings() {
  MatchSetting vga{{640, 480}, 64, kBlockSize};
  MatchSetting target = kTarget;
  vga.leftBand = target.leftBand = 16;
  return {vga, target};
}

std::vector<const Backend*> availableBackends() {
  std::vector<const Backend*> backends;
  for (const Backend* backend : registeredBackends()) {
    if (backend->available) backends.push_back(backend);
  }
  return backends;
}

// Built by appending: GCC 12 gives a false -Wrestrict on "literal" + string.
std::string sizeTag(FrameSize size) {
  std::string tag = std::to_string(size.width);
  tag += 'x';
  tag += std::to_string(size.height);
  return tag;
}

std::string matchTag(const MatchSetting& setting, int threads) {
  std::string tag = "d";
  tag += std::to_string(setting.numDisparities);
  tag += "/w";
  tag += std::to_string(setting.blockSize);
  if (setting.preFilter == PreFilterType::NormalizedResponse) tag += "/norm";
  tag += "/t";
  tag += std::to_string(threads);
  if (setting.leftBand > 0) {
    tag += "/band";
    tag += std::to_string(setting.leftBand);
  }
  return tag;
}

StereoParams frontendParams(const MatchSetting& setting) {
  StereoParams params;
  params.numDisparities = setting.numDisparities;
  params.blockSize = setting.blockSize;
  params.preFilterType = setting.preFilter;
  params.leftBand = setting.leftBand;
  return params;
}

StereoParams matchParams(const MatchSetting& setting) {
  StereoParams params = frontendParams(setting);
  params.speckleWindowSize = 0;
  return params;
}

void setPixelCounters(benchmark::State& state, FrameSize size) {
  const double megapixels = size.width * static_cast<double>(size.height) / 1e6;
  state.counters["Mpix/s"] =
      benchmark::Counter(megapixels, benchmark::Counter::kIsIterationInvariantRate);
}

void setPixelCounters(benchmark::State& state, const MatchSetting& setting) {
  setPixelCounters(state, setting.size);
  const double megapixels = setting.size.width * static_cast<double>(setting.size.height) / 1e6;
  state.counters["Mpix*disp/s"] = benchmark::Counter(megapixels * setting.numDisparities,
                                                     benchmark::Counter::kIsIterationInvariantRate);
}

benchmark::internal::Benchmark* measure(benchmark::internal::Benchmark* row) {
  return row->Unit(benchmark::kMillisecond);
}

void copyPixels(const Image& src, Image& dst) {
  const std::size_t rowBytes = static_cast<std::size_t>(src.width()) * pixelBytes(src.type());
  for (int y = 0; y < src.height(); ++y)
    std::memcpy(dst.row<std::uint8_t>(y), src.row<std::uint8_t>(y), rowBytes);
}

}  // namespace horopter::bench
