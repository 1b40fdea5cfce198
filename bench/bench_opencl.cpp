// OpenCL rows, registered at static initialisation (main() registers the
// CPU rows after them):
//   disparity/<opencl backend>/<size>/d<D>/w<W>/kernels     device time of the kernels
//       only (prefilter x2, matching, left-right check), from profiling events,
//       with one counter per stage in ms
//   disparity/<opencl backend>/<size>/d<D>/w<W>/transfers   wall time of a frame
//       end to end: upload, kernels, download (OpenClFrontend::computeDisparity)
//   disparity/<opencl backend>/.../transfers_inflight2      the same with two frames
//       in flight (submit the next before waiting for the previous): throughput
//   opencv_stereobm_ocl/<size>/d<D>/w<W>                   cv::StereoBM through
//       cv::UMat on OpenCV's OpenCL device, with upload and download, as ours
// The chain is the disparity/ rows' one: speckle filter and median off.
// OpenCV takes its OpenCL StereoBM only with textureThreshold 0 and, on PoCL,
// only with OPENCV_OPENCL_DEVICE=:CPU:, which is set here (unless the
// environment already sets it) before OpenCV's first OpenCL use.
#include <benchmark/benchmark.h>
#include <stdlib.h>

#include <map>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/core/ocl.hpp>
#include <string>

#include "bench_inputs.hpp"
#include "bench_support.hpp"
#include "horopter/eval/stereo_eval.hpp"
#include "horopter/kernels/backend.hpp"
#include "horopter/vision/opencl_frontend.hpp"
#include "horopter/vision/opencv.hpp"

namespace horopter::bench {

namespace {

MedianParams noMedian() {
  MedianParams m;
  m.kernelSize = 0;
  return m;
}

bool isTransfer(const std::string& stage) {
  return stage.rfind("upload", 0) == 0 || stage.rfind("download", 0) == 0;
}

void runKernelsOnly(benchmark::State& state, const std::string& device,
                    const MatchSetting& setting) {
  const StereoPair& pair = stereoPair(setting.size);
  OpenClFrontend frontend(matchParams(setting), noMedian(), device, 1);
  if (frontend.onCpu()) {
    state.SkipWithError(("OpenCL fell back to the CPU: " + frontend.fallbackReason()).c_str());
    return;
  }
  frontend.computeDisparity(pair.left.view(), pair.right.view());  // first-use setup
  std::map<std::string, double> stageMs;
  for (auto _ : state) {
    frontend.computeDisparity(pair.left.view(), pair.right.view());
    double kernelMs = 0;
    for (const OpenClStageTime& t : frontend.profile()) {
      stageMs[t.stage] += t.ms;
      if (t.onDevice && !isTransfer(t.stage)) kernelMs += t.ms;
    }
    state.SetIterationTime(kernelMs * 1e-3);
  }
  for (const auto& [stage, ms] : stageMs)
    state.counters[stage + " ms"] = benchmark::Counter(ms, benchmark::Counter::kAvgIterations);
  state.SetLabel(frontend.deviceName());
  setPixelCounters(state, setting);
}

void runWithTransfers(benchmark::State& state, const std::string& device,
                      const MatchSetting& setting, int inFlight) {
  const StereoPair& pair = stereoPair(setting.size);
  OpenClFrontend frontend(matchParams(setting), noMedian(), device, inFlight);
  if (frontend.onCpu()) {
    state.SkipWithError(("OpenCL fell back to the CPU: " + frontend.fallbackReason()).c_str());
    return;
  }
  frontend.computeDisparity(pair.left.view(), pair.right.view());
  if (inFlight == 1) {
    for (auto _ : state)
      frontend.computeDisparity(pair.left.view(), pair.right.view());
  } else {
    // Keep inFlight - 1 frames queued ahead of the one waited for.
    std::vector<OpenClFrontend::Ticket> queued;
    for (int i = 0; i + 1 < inFlight; ++i)
      queued.push_back(frontend.submit(pair.left.view(), pair.right.view()));
    for (auto _ : state) {
      queued.push_back(frontend.submit(pair.left.view(), pair.right.view()));
      frontend.wait(queued.front());
      queued.erase(queued.begin());
    }
    for (OpenClFrontend::Ticket t : queued)
      frontend.wait(t);
  }
  state.SetLabel(frontend.deviceName());
  setPixelCounters(state, setting);
}

void runOpenCvOcl(benchmark::State& state, const MatchSetting& setting) {
  if (!cv::ocl::haveOpenCL()) {
    state.SkipWithError("OpenCV sees no OpenCL device");
    return;
  }
  cv::ocl::setUseOpenCL(true);
  const StereoPair& pair = stereoPair(setting.size);
  const cv::Mat leftMat = matOf(pair.left), rightMat = matOf(pair.right);
  StereoParams params = matchParams(setting);
  params.textureThreshold = 0;  // else OpenCV quietly runs its CPU path
  const cv::Ptr<cv::StereoBM> bm = makeOpenCvStereoBM(params);
  cv::UMat left, right, disparity;
  cv::Mat result;
  auto frame = [&] {
    leftMat.copyTo(left);
    rightMat.copyTo(right);
    bm->compute(left, right, disparity);
    disparity.copyTo(result);
  };
  frame();  // compiles OpenCV's kernels
  for (auto _ : state)
    frame();
  state.SetLabel(cv::ocl::Device::getDefault().name());
  setPixelCounters(state, setting);
}

bool registerRows() {
  // Before OpenCV's first OpenCL use: PoCL is a CPU device, which OpenCV
  // skips unless told.
  ::setenv("OPENCV_OPENCL_DEVICE", ":CPU:", 0);
  for (const MatchSetting& setting : matchSettings(/*withTarget=*/false)) {
    const std::string tail = sizeTag(setting.size) + "/d" + std::to_string(setting.numDisparities) +
                             "/w" + std::to_string(setting.blockSize);
    for (const Backend* backend : availableBackends()) {
      if (backend->name.rfind("opencl", 0) != 0) continue;
      const std::string device = backend->name;
      const std::string base = "disparity/" + device + "/" + tail;
      measure(benchmark::RegisterBenchmark((base + "/kernels").c_str(), [device, setting](
                                                                            benchmark::State& s) {
        runKernelsOnly(s, device, setting);
      }))->UseManualTime();
      measure(benchmark::RegisterBenchmark((base + "/transfers").c_str(), [device, setting](
                                                                              benchmark::State& s) {
        runWithTransfers(s, device, setting, 1);
      }))->UseRealTime();
      measure(benchmark::RegisterBenchmark((base + "/transfers_inflight2").c_str(),
                                           [device, setting](benchmark::State& s) {
                                             runWithTransfers(s, device, setting, 2);
                                           }))
          ->UseRealTime();
    }
    measure(
        benchmark::RegisterBenchmark(("opencv_stereobm_ocl/" + tail).c_str(),
                                     [setting](benchmark::State& s) { runOpenCvOcl(s, setting); }))
        ->UseRealTime();
  }
  return true;
}

const bool registered = registerRows();

}  // namespace

}  // namespace horopter::bench
