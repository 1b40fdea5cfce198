// Ours against the peer on the same frames: disparity/<backend>/... runs the
// kernels cv::StereoBM's compute() amounts to (x-Sobel prefilter of both
// views, SAD matching with texture, uniqueness and sub-pixel, left-right
// check; speckle filter off in both), opencv_stereobm/... runs cv::StereoBM.
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

#include "bench_inputs.hpp"
#include "bench_support.hpp"
#include "horopter/kernels.hpp"
#include "horopter/opencv.hpp"
#include "horopter/stereo_eval.hpp"
#include "registration.hpp"

namespace horopter::bench {

namespace {

constexpr int kPeerThreads[] = {1, 2};

void runOurs(benchmark::State& state, const Backend& backend, const MatchSetting& setting) {
  const StereoPair& pair = stereoPair(setting.size);
  const StereoParams params = matchParams(setting);
  const int width = setting.size.width;
  const int height = setting.size.height;
  Image leftFiltered(width, height, PixelType::U8C1);
  Image rightFiltered(width, height, PixelType::U8C1);
  Image texture(width, height, PixelType::U8C1);
  Image disparity(width, height, PixelType::S16C1);
  Image winnerRight(width, height, PixelType::S16C1);

  for (auto _ : state) {
    prefilterXSobel(pair.left.view(), params.preFilterCap, leftFiltered.view(), texture.view(),
                    backend);
    prefilterXSobel(pair.right.view(), params.preFilterCap, rightFiltered.view(), {}, backend);
    matchBlocks(leftFiltered.view(), rightFiltered.view(), texture.view(), params, disparity.view(),
                winnerRight.view(), backend);
    leftRightCheck(disparity.view(), winnerRight.view(), params, backend);
  }
  setPixelCounters(state, setting);
}

// Sets OpenCV's thread count for one row and puts the previous one back.
class OpenCvThreads {
 public:
  explicit OpenCvThreads(int threads) : previous_(cv::getNumThreads()) {
    cv::setNumThreads(threads);
  }
  ~OpenCvThreads() { cv::setNumThreads(previous_); }
  OpenCvThreads(const OpenCvThreads&) = delete;
  OpenCvThreads& operator=(const OpenCvThreads&) = delete;

 private:
  int previous_;
};

void runPeer(benchmark::State& state, const MatchSetting& setting, int threads) {
  const StereoPair& pair = stereoPair(setting.size);
  const cv::Mat left = matOf(pair.left);
  const cv::Mat right = matOf(pair.right);
  const cv::Ptr<cv::StereoBM> bm = makeOpenCvStereoBM(matchParams(setting));
  // Allocated by the first compute() and reused by the others.
  cv::Mat disparity;

  const OpenCvThreads scope(threads);
  for (auto _ : state)
    bm->compute(left, right, disparity);
  setPixelCounters(state, setting);
}

}  // namespace

void registerDisparityRows() {
  for (const MatchSetting& setting : matchSettings(/*withTarget=*/true)) {
    for (const Backend* backend : availableBackends()) {
      const std::string name = "disparity/" + backend->name + "/" + sizeTag(setting.size) + "/" +
                               matchTag(setting, kOurThreads);
      measure(benchmark::RegisterBenchmark(
          name.c_str(),
          [backend, setting](benchmark::State& state) { runOurs(state, *backend, setting); }));
    }
    for (const int threads : kPeerThreads) {
      const std::string name =
          "opencv_stereobm/" + sizeTag(setting.size) + "/" + matchTag(setting, threads);
      auto* row = measure(benchmark::RegisterBenchmark(
          name.c_str(),
          [setting, threads](benchmark::State& state) { runPeer(state, setting, threads); }));
      // CPU time counts the calling thread only; with worker threads, time
      // the wall clock (Google Benchmark appends "/real_time" to the name).
      if (threads > 1) row->UseRealTime();
    }
  }
}

}  // namespace horopter::bench
