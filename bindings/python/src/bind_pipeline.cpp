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
#include "horopter/app/pipeline_builder.hpp"
#include "horopter/core/error.hpp"
#include "horopter/movement/movement_classifier.hpp"
#include "horopter/sim/synthetic_source.hpp"
#include "pipeline_args.hpp"
#include "stereo_args.hpp"

namespace horopter::python {

namespace {

class PipelineRun {
 public:
  PipelineRun(const PipelineConfig& config, const sim::SyntheticSourceOptions& synthetic)
      : capacity_(static_cast<std::size_t>(config.inFlight)) {
    PipelineHooks hooks;
    hooks.openSource = sim::syntheticSourceOpener(synthetic);
    hooks.stopRequested = &stop_;
    hooks.onFrame = [this](const Frame& f) { push(f); };
    pipeline_ = std::make_unique<AssembledPipeline>(buildPipeline(config, std::move(hooks)));
    sourceName_ = pipeline_->source().name();
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
  // The frames' digest as `horopter run --json` prints it (after the run).
  py::object digest() const {
    std::lock_guard lock(mutex_);
    if (!finished_) return py::none();
    return py::str(digestText(digest_));
  }

 private:
  void push(const Frame& f) {
    digest_ = foldDigest(digest_, frameDigest(f));  // frames come in order, on one thread
    // Mat headers: the pixels are shared, not copied. A simulated frame keeps
    // its type, and so its truth.
    const auto* simulated = dynamic_cast<const sim::SimFrame*>(&f);
    std::unique_ptr<Frame> copy = simulated != nullptr ? std::make_unique<sim::SimFrame>(*simulated)
                                                       : std::make_unique<Frame>(f);
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
      summary = pipeline_->run();
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
  std::unique_ptr<AssembledPipeline> pipeline_;
  std::uint64_t digest_ = 0;
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
      .def(py::init([](const std::string& source, std::optional<std::int64_t> frames,
                       const py::object& params, const py::object& median,
                       const std::string& backend, int threads, int inFlight, bool live,
                       std::optional<std::pair<int, int>> size, std::uint64_t seed,
                       const std::string& calib, double fixation,
                       std::optional<double> fixationDisparity, std::optional<double> focalPx,
                       const std::optional<std::string>& detect,
                       const std::shared_ptr<MovementModel>& movementModel, bool headControl,
                       const py::kwargs& kwargs) {
             PipelineConfig c;
             sim::SyntheticSourceOptions synthetic;
             c.source = source;
             if (frames) {
               if (*frames < 1) throw py::value_error("frames must be >= 1");
               c.maxFrames = *frames;
               synthetic.frames = static_cast<int>(*frames);
             }
             c.stereo = params.is_none() ? runStereoDefaults() : params.cast<StereoParams>();
             applyPipelineKwargs(c, kwargs);
             c.median = median.is_none() ? MedianParams{} : median.cast<MedianParams>();
             c.backend = backend;
             c.threads = threads;
             c.inFlight = inFlight;
             c.live = live;
             if (size) {
               c.capture.width = synthetic.scene.width = size->first;
               c.capture.height = synthetic.scene.height = size->second;
             }
             synthetic.scene.seed = seed;
             c.zone.calib = calib;
             c.zone.fixationDistanceM = fixation;
             c.zone.fixationDisparityPx = fixationDisparity;
             c.zone.focalPx = focalPx;
             c.detection.reset();
             if (detect) {
               if (*detect != "region" && *detect != "full")
                 throw py::value_error("detect takes 'region', 'full' or None, got '" + *detect +
                                       "'");
               c.detection =
                   *detect == "full" ? DetectionScope::FullImage : DetectionScope::HoropterRegion;
             }
             c.headControl = headControl;
             if (movementModel && !detect)
               throw py::value_error(
                   "movement_model needs detect='region' or 'full' (movement analysis follows "
                   "the tracked body)");
             c.movement = movementModel;
             return std::make_unique<PipelineRun>(c, synthetic);
           }),
           py::arg("source") = "synthetic", py::arg("frames") = py::none(),
           py::arg("params") = py::none(), py::arg("median") = py::none(),
           py::arg("backend") = "auto", py::arg("threads") = 1, py::arg("in_flight") = 3,
           py::arg("live") = false, py::arg("size") = py::none(), py::arg("seed") = 1,
           py::arg("calib") = "", py::arg("fixation") = 1.5,
           py::arg("fixation_disparity") = py::none(), py::arg("focal_px") = py::none(),
           py::arg("detect") = py::none(), py::arg("movement_model") = py::none(),
           py::arg("head_control") = true,
           "Pipeline(source='synthetic', frames=None, params=None, median=None, "
           "backend='auto', threads=1, in_flight=3, live=False, size=None, seed=1, calib='', "
           "fixation=1.5, fixation_disparity=None, focal_px=None, detect=None, "
           "movement_model=None, head_control=True, **options): the pipeline of "
           "`horopter run` for the same configuration. detect='region' or 'full' adds face and "
           "hand detection and tracking (frame['detections'], ['tracking'], ['body']); on the "
           "synthetic scene (offline, no calib) the head control then turns the cameras "
           "(head_control=False: they stay still); "
           "movement_model (a MovementModel) then adds movement analysis (frame['movement']). "
           "params=None: the run's stereo defaults (StereoParams() with leftBand=16, as "
           "`horopter run`). options: StereoParams fields (numDisparities=64, ...) and the "
           "tuning options of "
           "horopter.tuning_options() by name (zoneSearch=1, trackDepthGatePx=..., ...). "
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
      .def_property_readonly("source", &PipelineRun::sourceName)
      .def_property_readonly("digest", &PipelineRun::digest,
                             "After the run: the frames' digest (hex), as `horopter run --json` "
                             "prints it for the same configuration; else None");
}

}  // namespace horopter::python
