// The scheduler: capture on the caller's thread, one lane (thread) per stage,
// in-flight slots for back-pressure (taken before capture offline, after it
// live), a one-frame mailbox for live mode.
#include "horopter/pipeline/scheduler.hpp"

#include <algorithm>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>

#include "horopter/core/error.hpp"
#include "pipeline/frame_queue.hpp"

namespace horopter {

namespace {

using pipeline_detail::FrameQueue;

// Stands in for the stages of a pipeline that has none, so that frames still
// go from capture to onFrame through one lane.
class PassStage final : public ScheduledStage {
 public:
  std::string name() const override { return "pass"; }
  void run(ScheduledFrame&) override {}
};

double msBetween(SteadyClock::time_point a, SteadyClock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

// Caps the trace of a long live run (about 100 bytes an event).
constexpr std::size_t kMaxTraceEvents = 200000;

// The state of one run, shared by the capture loop and the lanes.
class Run {
 public:
  Run(const SchedulerOptions& options, std::vector<std::unique_ptr<ScheduledStage>>& stages)
      : options_(options),
        stages_(stages),
        queues_(stages.size() + 1),
        stageMs_(stages.size(), 0.0),
        stageFrames_(stages.size(), 0),
        freeSlots_(options.inFlight),
        start_(SteadyClock::now()) {
    for (const auto& stage : stages_)
      names_.push_back(stage->name());
  }

  RunSummary execute(ScheduledSource& source) {
    std::vector<std::thread> lanes;
    lanes.reserve(stages_.size());
    for (std::size_t i = 0; i < stages_.size(); ++i)
      lanes.emplace_back([this, i] { laneLoop(i); });
    capture(source);
    queues_[0].close();
    for (auto& lane : lanes)
      lane.join();
    return summarize(source.name());
  }

 private:
  bool aborted() const { return aborted_.load(std::memory_order_acquire); }

  // Records the first failure and makes everything wind down.
  void fail(const std::string& stage, std::int64_t frame, const std::string& what) {
    {
      std::lock_guard lock(errorMutex_);
      if (!error_)
        error_ = "stage '" + stage + "' failed on frame " + std::to_string(frame) + ": " + what;
    }
    aborted_.store(true, std::memory_order_release);
    for (auto& q : queues_)
      q.close();
    slotFreed_.notify_all();
  }

  bool stopRequested() const {
    return options_.stopRequested && options_.stopRequested->load(std::memory_order_relaxed);
  }

  void capture(ScheduledSource& source) {
    const bool live = options_.mode == PipelineMode::Live;
    for (std::int64_t index = 0; !aborted(); ++index) {
      if (options_.maxFrames >= 0 && index >= options_.maxFrames) break;
      if (stopRequested()) {
        stoppedByRequest_ = true;
        break;
      }
      // Offline, a frame takes its slot before its capture starts: with K in
      // flight, frame N + K - 1 is captured while frame N is in the stages
      // (one in flight is one frame at a time, capture included).
      if (!live) {
        if (!takeSlot()) break;
        if (stopRequested()) {
          stoppedByRequest_ = true;
          releaseSlot();
          break;
        }
      }
      std::unique_ptr<ScheduledFrame> frame = source.newFrame();
      if (!frame) {
        if (!live) releaseSlot();
        fail("capture", index, "the source made no frame");
        return;
      }
      frame->index = index;
      const auto t0 = SteadyClock::now();
      bool got = false;
      try {
        got = source.fill(*frame);
      } catch (const std::exception& e) {
        if (!live) releaseSlot();
        fail("capture", index, e.what());
        return;
      }
      if (!got) {
        if (!live) releaseSlot();
        break;
      }
      const auto t1 = SteadyClock::now();
      frame->captured = t1;
      frame->spans.push_back({"capture", t0, t1});
      captureMs_ += msBetween(t0, t1);
      ++captured_;
      if (live)
        admitLive(std::move(frame));
      else
        queues_[0].push(std::move(frame));
    }
    // Live mode: the frame left in the mailbox is the newest; let it in.
    std::unique_ptr<ScheduledFrame> last;
    {
      std::lock_guard lock(slotMutex_);
      last = std::move(mailbox_);
    }
    if (last) admitWaiting(std::move(last));
  }

  // Waits for a free slot and takes it; false when the run was aborted.
  bool takeSlot() {
    std::unique_lock lock(slotMutex_);
    slotFreed_.wait(lock, [&] { return freeSlots_ > 0 || aborted(); });
    if (aborted()) return false;
    --freeSlots_;
    return true;
  }

  // Waits for a free slot, then sends the frame in.
  void admitWaiting(std::unique_ptr<ScheduledFrame> frame) {
    if (takeSlot()) queues_[0].push(std::move(frame));
  }

  // Sends the frame in if a slot is free; otherwise it waits in the mailbox,
  // replacing (dropping) an older one.
  void admitLive(std::unique_ptr<ScheduledFrame> frame) {
    std::unique_lock lock(slotMutex_);
    if (freeSlots_ > 0) {
      --freeSlots_;
      lock.unlock();
      queues_[0].push(std::move(frame));
      return;
    }
    if (mailbox_) ++dropped_;
    mailbox_ = std::move(frame);
  }

  // A frame left the pipeline: its slot goes to the mailbox's frame, if any.
  void releaseSlot() {
    std::unique_ptr<ScheduledFrame> waiting;
    {
      std::lock_guard lock(slotMutex_);
      if (mailbox_ && !aborted())
        waiting = std::move(mailbox_);
      else
        ++freeSlots_;
    }
    if (waiting)
      queues_[0].push(std::move(waiting));
    else
      slotFreed_.notify_all();
  }

  void laneLoop(std::size_t i) {
    ScheduledStage& stage = *stages_[i];
    const std::string& name = names_[i];
    const bool last = i + 1 == stages_.size();
    while (auto frame = queues_[i].pop()) {
      if (aborted()) {
        releaseSlot();
        continue;
      }
      const auto t0 = SteadyClock::now();
      try {
        stage.run(*frame);
      } catch (const std::exception& e) {
        fail(name, frame->index, e.what());
        releaseSlot();
        continue;
      }
      const auto t1 = SteadyClock::now();
      frame->spans.push_back({name, t0, t1});
      stageMs_[i] += msBetween(t0, t1);
      ++stageFrames_[i];
      if (last)
        finish(std::move(frame));
      else
        queues_[i + 1].push(std::move(frame));
    }
    if (!last) queues_[i + 1].close();
  }

  void finish(std::unique_ptr<ScheduledFrame> frame) {
    const auto end = SteadyClock::now();
    const double latency = msBetween(frame->captured, end);
    latencySumMs_ += latency;
    maxLatencyMs_ = std::max(maxLatencyMs_, latency);
    ++completed_;
    recordTrace(*frame);
    if (options_.onFrame) {
      try {
        options_.onFrame(*frame);
      } catch (const std::exception& e) {
        fail("output", frame->index, e.what());
      }
    }
    frame.reset();
    releaseSlot();
  }

  void recordTrace(const ScheduledFrame& frame) {
    for (const StageSpan& span : frame.spans) {
      if (trace_.size() >= kMaxTraceEvents) return;
      int lane = 0;
      for (std::size_t i = 0; i < names_.size(); ++i)
        if (span.stage == names_[i]) lane = static_cast<int>(i) + 1;
      trace_.push_back({span.stage, frame.index, lane,
                        std::chrono::duration<double, std::micro>(span.start - start_).count(),
                        std::chrono::duration<double, std::micro>(span.end - span.start).count()});
    }
  }

  RunSummary summarize(const std::string& sourceName) {
    if (error_) throw Error(*error_);
    RunSummary s;
    s.seconds = std::chrono::duration<double>(SteadyClock::now() - start_).count();
    s.captured = captured_;
    s.completed = completed_;
    s.dropped = dropped_;
    s.meanLatencyMs = completed_ > 0 ? latencySumMs_ / static_cast<double>(completed_) : 0;
    s.maxLatencyMs = maxLatencyMs_;
    s.stoppedByRequest = stoppedByRequest_;
    s.stages.push_back({"capture (" + sourceName + ")", captured_,
                        captured_ > 0 ? captureMs_ / static_cast<double>(captured_) : 0});
    for (std::size_t i = 0; i < stages_.size(); ++i) {
      const auto n = stageFrames_[i];
      s.stages.push_back({names_[i], n, n > 0 ? stageMs_[i] / static_cast<double>(n) : 0});
    }
    s.trace = std::move(trace_);
    return s;
  }

  const SchedulerOptions& options_;
  std::vector<std::unique_ptr<ScheduledStage>>& stages_;
  std::vector<std::string> names_;  // the stages' names, asked once
  // queues_[i] feeds stage i; the last one is unused (the last lane finishes frames).
  std::vector<FrameQueue> queues_;
  // Written by lane i only; read after the joins.
  std::vector<double> stageMs_;
  std::vector<std::int64_t> stageFrames_;
  // Written by the last lane only (finish), read after the joins.
  std::vector<TraceEvent> trace_;
  double latencySumMs_ = 0, maxLatencyMs_ = 0;
  std::int64_t completed_ = 0;
  // Written by the capture loop only.
  double captureMs_ = 0;
  std::int64_t captured_ = 0;
  bool stoppedByRequest_ = false;

  std::mutex slotMutex_;
  std::condition_variable slotFreed_;
  int freeSlots_;
  std::unique_ptr<ScheduledFrame> mailbox_;
  std::int64_t dropped_ = 0;

  std::atomic<bool> aborted_{false};
  std::mutex errorMutex_;
  std::optional<std::string> error_;
  const SteadyClock::time_point start_;
};

}  // namespace

ScheduledFrame::~ScheduledFrame() = default;
ScheduledSource::~ScheduledSource() = default;
ScheduledStage::~ScheduledStage() = default;

void validate(const SchedulerOptions& options) {
  if (options.inFlight < 1 || options.inFlight > 64)
    throw Error("frames in flight must be 1..64, got " + std::to_string(options.inFlight));
  if (options.maxFrames < -1)
    throw Error("maxFrames must be -1 (no limit) or >= 0, got " +
                std::to_string(options.maxFrames));
}

Scheduler::Scheduler(SchedulerOptions options) : options_(std::move(options)) {
  validate(options_);
}

Scheduler::~Scheduler() = default;

Scheduler& Scheduler::add(std::unique_ptr<ScheduledStage> stage) {
  if (!stage) throw Error("Pipeline::add: null stage");
  const std::string name = stage->name();
  if (name.empty()) throw Error("a pipeline stage needs a name");
  if (name == "capture" || name == "output")
    throw Error("'" + name + "' is the name of the pipeline's own step: name the stage otherwise");
  for (const auto& s : stages_)
    if (s->name() == name) throw Error("two pipeline stages are named '" + name + "'");
  stages_.push_back(std::move(stage));
  return *this;
}

RunSummary Scheduler::run(ScheduledSource& source) {
  if (stages_.empty()) stages_.push_back(std::make_unique<PassStage>());
  Run run(options_, stages_);
  return run.execute(source);
}

}  // namespace horopter
