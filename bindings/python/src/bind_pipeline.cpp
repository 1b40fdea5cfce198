// The frame pipeline from Python: the pipeline runs on its own thread
// (capture, rectify, disparity, mask lanes, no Python there); each finished
// frame is queued, and iterating the Pipeline object yields it as a dict of
// numpy arrays sharing the frame's memory. The queue holds at most
// `in_flight` frames, so a slow consumer slows capture (offline mode) or
// makes it drop stale frames (live mode), as the pipeline's own back-pressure.
#include <pybind11/stl.h>

#include <atomic>
#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <thread>

#include "bindings.hpp"
#include "frame_dicts.hpp"
#include "horopter/capture.hpp"
#include "horopter/detection.hpp"
#include "horopter/error.hpp"
#include "horopter/movement.hpp"
#include "horopter/movement_classifier.hpp"
#include "horopter/tracking.hpp"
#include "horopter/vision_stages.hpp"
#include "pipeline_zone.hpp"
#include "stereo_args.hpp"

namespace horopter::python {

namespace {

struct RunConfig {
  std::string source = "synthetic";
  CaptureOptions capture;
  std::int64_t maxFrames = -1;
  StereoParams stereo;
  MedianParams median;
  std::string backend = "auto";
  int threads = 1;
  int inFlight = 3;
  bool live = false;
  ZoneOptions zone;
  std::string detect;                             // "", "region" or "full"
  std::shared_ptr<const MovementModel> movement;  // needs detect
};

class PipelineRun {
 public:
  explicit PipelineRun(const RunConfig& config)
      : capacity_(static_cast<std::size_t>(config.inFlight)) {
    const Backend& backend = findBackend(config.backend);
    source_ = openSource(config.source, config.capture);
    const ZoneSetup zone = zoneSetup(*source_, config.zone, config.stereo);
    PipelineOptions options;
    options.mode = config.live ? PipelineMode::Live : PipelineMode::Offline;
    options.inFlight = config.inFlight;
    options.maxFrames = config.maxFrames;
    options.stopRequested = &stop_;
    options.onFrame = [this](const Frame& f) { push(f); };
    pipeline_ = std::make_unique<Pipeline>(options);
    pipeline_->add(makeRectifyStage(zone.rectify));
    pipeline_->add(makeDisparityStage(config.stereo, config.median, backend, config.threads));
    pipeline_->add(makeMaskStage(zone.thresholds, config.stereo, backend));
    if (!config.detect.empty()) {  // as `horopter run` (without its head control)
      DetectorOptions detector;
      detector.scope =
          config.detect == "full" ? DetectionScope::FullImage : DetectionScope::HoropterRegion;
      pipeline_->add(makeDetectionStage(detector));
      TrackerOptions tracker;
      tracker.rig = zone.rig;
      tracker.framesPerSecond = zone.framesPerSecond;
      tracker.captureTime = config.live;
      pipeline_->add(makeTrackingStage(tracker));
      if (config.movement) pipeline_->add(makeMovementStage(config.movement));
    }
    sourceName_ = source_->name();
    thread_ = std::thread([this] { runPipeline(); });
  }

  ~PipelineRun() { close(); }
  PipelineRun(const PipelineRun&) = delete;
  PipelineRun& operator=(const PipelineRun&) = delete;

  // The next finished frame as a dict; StopIteration at the end; the
  // pipeline's error, if it failed.
  py::dict next() {
    std::unique_ptr<Frame> frame;
    {
      py::gil_scoped_release release;
      std::unique_lock lock(mutex_);
      changed_.wait(lock, [&] { return !queue_.empty() || finished_; });
      if (!queue_.empty()) {
        frame = std::move(queue_.front());
        queue_.pop_front();
        changed_.notify_all();
      }
    }
    if (frame) return frameDict(*frame);
    if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
    throw py::stop_iteration();
  }

  // Stops capture, lets the frames in flight finish, and joins the thread.
  void close() {
    stop_ = true;
    {
      std::lock_guard lock(mutex_);
      closed_ = true;
      queue_.clear();
    }
    changed_.notify_all();
    if (thread_.joinable()) {
      py::gil_scoped_release release;
      thread_.join();
    }
  }

  py::object summary() const {
    std::lock_guard lock(mutex_);
    if (!finished_) return py::none();
    return py::module_::import("json").attr("loads")(summaryJson(summary_));
  }
  const std::string& sourceName() const { return sourceName_; }

 private:
  void push(const Frame& f) {
    auto copy = std::make_unique<Frame>(f);  // Mat headers: the pixels are shared, not copied
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return queue_.size() < capacity_ || closed_; });
    if (closed_) return;
    queue_.push_back(std::move(copy));
    changed_.notify_all();
  }

  void runPipeline() {
    RunSummary summary;
    std::exception_ptr error;
    try {
      summary = pipeline_->run(*source_);
    } catch (...) {
      error = std::current_exception();
    }
    std::lock_guard lock(mutex_);
    summary_ = std::move(summary);
    error_ = error;
    finished_ = true;
    changed_.notify_all();
  }

  std::size_t capacity_;
  std::unique_ptr<FrameSource> source_;
  std::unique_ptr<Pipeline> pipeline_;
  std::string sourceName_;
  std::atomic<bool> stop_{false};
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<std::unique_ptr<Frame>> queue_;
  bool closed_ = false, finished_ = false;
  std::exception_ptr error_;
  RunSummary summary_;
  std::thread thread_;
};

}  // namespace

void bindPipeline(py::module_& m) {
  py::class_<PipelineRun>(m, "Pipeline",
                          "Runs a source through rectify -> disparity -> mask with several "
                          "frames in flight; iterate it for one dict per finished frame")
      .def(py::init(
               [](const std::string& source, std::optional<std::int64_t> frames,
                  const py::object& params, const py::object& median, const std::string& backend,
                  int threads, int inFlight, bool live, std::optional<std::pair<int, int>> size,
                  std::uint64_t seed, const std::string& calib, double fixation,
                  std::optional<double> fixationDisparity, std::optional<double> focalPx,
                  const std::optional<std::string>& detect,
                  const std::shared_ptr<MovementModel>& movementModel, const py::kwargs& kwargs) {
                 RunConfig c;
                 c.source = source;
                 if (frames) {
                   if (*frames < 1) throw py::value_error("frames must be >= 1");
                   c.maxFrames = *frames;
                   c.capture.frames = static_cast<int>(*frames);
                 }
                 c.stereo = params.is_none() ? StereoParams{} : params.cast<StereoParams>();
                 applyStereoKwargs(c.stereo, kwargs);
                 c.median = median.is_none() ? MedianParams{} : median.cast<MedianParams>();
                 c.backend = backend;
                 c.threads = threads;
                 c.inFlight = inFlight;
                 c.live = live;
                 if (size) {
                   c.capture.width = c.capture.scene.width = size->first;
                   c.capture.height = c.capture.scene.height = size->second;
                 }
                 c.capture.scene.seed = seed;
                 c.zone.calib = calib;
                 c.zone.fixation = fixation;
                 c.zone.fixationDisparity = fixationDisparity;
                 c.zone.focalPx = focalPx;
                 if (detect) {
                   if (*detect != "region" && *detect != "full")
                     throw py::value_error("detect takes 'region', 'full' or None, got '" +
                                           *detect + "'");
                   c.detect = *detect;
                 }
                 if (movementModel && !detect)
                   throw py::value_error(
                       "movement_model needs detect='region' or 'full' (movement analysis follows "
                       "the tracked body)");
                 c.movement = movementModel;
                 return std::make_unique<PipelineRun>(c);
               }),
           py::arg("source") = "synthetic", py::arg("frames") = py::none(),
           py::arg("params") = py::none(), py::arg("median") = py::none(),
           py::arg("backend") = "auto", py::arg("threads") = 1, py::arg("in_flight") = 3,
           py::arg("live") = false, py::arg("size") = py::none(), py::arg("seed") = 1,
           py::arg("calib") = "", py::arg("fixation") = 1.5,
           py::arg("fixation_disparity") = py::none(), py::arg("focal_px") = py::none(),
           py::arg("detect") = py::none(), py::arg("movement_model") = py::none(),
           "Pipeline(source='synthetic', frames=None, params=None, median=None, "
           "backend='auto', threads=1, in_flight=3, live=False, size=None, seed=1, calib='', "
           "fixation=1.5, fixation_disparity=None, focal_px=None, detect=None, "
           "movement_model=None, **stereo_kwargs). detect='region' or 'full' adds face and "
           "hand detection and tracking (frame['detections'], ['tracking'], ['body']); "
           "movement_model (a MovementModel) then adds movement analysis (frame['movement']). "
           "Sources: "
           "synthetic, dir:PATH, video:LEFT,RIGHT, camera:DEV,DEV, sbs:DEV (as horopter run)")
      .def("__iter__", [](py::object self) { return self; })
      .def("__next__", &PipelineRun::next)
      .def("close", &PipelineRun::close, "Stops capture, finishes the frames in flight")
      .def("__enter__", [](py::object self) { return self; })
      .def("__exit__",
           [](PipelineRun& run, const py::args&) {
             run.close();
             return false;
           })
      .def_property_readonly("summary", &PipelineRun::summary,
                             "After the run: frames, fps, latency, stages (a dict), else None")
      .def_property_readonly("source", &PipelineRun::sourceName);
}

}  // namespace horopter::python
