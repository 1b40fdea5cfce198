// Ours against the peer on the same frames: disparity/<backend>/... runs the
// kernels cv::StereoBM's compute() amounts to (x-Sobel prefilter of both
// views, SAD matching with texture, uniqueness and sub-pixel, left-right
// check; speckle filter off in both), opencv_stereobm/... runs cv::StereoBM.
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

#include "bench_inputs.hpp"
#include "bench_support.hpp"
#include "horopter/eval/stereo_eval.hpp"
#include "horopter/vision/frontend.hpp"
#include "horopter/vision/opencv.hpp"
#include "registration.hpp"

namespace horopter::bench {

namespace {

// The front end with the median off and the speckle filter off in the
// parameters is exactly prefilter + matching + left-right check.
void runOurs(benchmark::State& state, const Backend& backend, const MatchSetting& setting,
             int threads) {
  const StereoPair& pair = stereoPair(setting.size);
  MedianParams noMedian;
  noMedian.kernelSize = 0;
  StereoFrontend frontend(matchParams(setting), noMedian, backend, threads);
  for (auto _ : state)
    frontend.computeDisparity(pair.left.view(), pair.right.view());
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
  const auto registerOurs = [](const MatchSetting& setting) {
    for (const Backend* backend : availableBackends()) {
      for (const int threads : kThreadCounts) {
        const std::string name = "disparity/" + backend->name + "/" + sizeTag(setting.size) + "/" +
                                 matchTag(setting, threads);
        auto* row = measure(benchmark::RegisterBenchmark(
            name.c_str(), [backend, setting, threads](benchmark::State& state) {
              runOurs(state, *backend, setting, threads);
            }));
        if (threads > 1) row->UseRealTime();
      }
    }
  };
  // The left band's rows: ours only (cv::StereoBM has no band).
  for (const MatchSetting& setting : bandSettings())
    registerOurs(setting);
  for (const MatchSetting& setting : matchSettings(/*withTarget=*/true)) {
    registerOurs(setting);
    for (const int threads : kThreadCounts) {
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
