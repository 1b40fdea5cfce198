// The scheduler: keeps several frames in flight through a chain of stages.
// It knows no application type: it moves ScheduledFrame objects, which the
// application derives its frame from (horopter/app/frame.hpp: Frame, Stage,
// FrameSource, Pipeline).
//
// A pipeline is a frame source (capture) followed by stages (rectify,
// disparity, mask, detection, ...). Each stage runs on its own lane, a thread
// that takes frames in order, so a stage may keep state between frames (the
// front end's buffers, a tracker) without locks, and frame N+1 can be in the
// disparity stage while frame N is in detection and frame N+2 is being
// captured. A stage that needs more than one core (the front end) brings its
// own work: it runs its kernels on the engine's thread pool from its lane.
//
// The number of frames in flight is bounded by SchedulerOptions::inFlight:
// that is the back-pressure.
//
//   Offline mode: a frame is in flight from the start of its capture to the
//     end of the last stage; capture waits for a free slot before it starts
//     (one in flight: one frame at a time, capture included; three: frame
//     N + 2 is captured while N + 1 and N are in the stages). Every frame is
//     processed, in order. Stage outputs depend only on the frame and on the frames before
//     it, so they are the same whatever the thread count or depth in flight.
//   Live mode: capture never waits. When every slot is taken, the newest
//     captured frame waits in a one-frame mailbox and replaces (drops) the one
//     that was waiting there: the newest frame wins, stale ones are counted as
//     dropped, and latency stays bounded.
//
// An exception in a stage or in the source stops the pipeline: the source
// stops, the lanes finish, every thread is joined, and run() throws a
// horopter::Error that names the stage and the frame. A stop request (Ctrl-C)
// stops capture and lets the frames already in flight finish.
#pragma once

#include "horopter/core/export.hpp"

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace horopter {

using SteadyClock = std::chrono::steady_clock;

// When a stage worked on a frame, for the summary and the trace.
struct HOROPTER_API StageSpan {
  std::string stage;
  SteadyClock::time_point start, end;
};

// What the scheduler knows of a frame: its place in the stream, when it was
// captured and when each stage worked on it. Applications derive their frame
// type from it; the scheduler only moves it from lane to lane.
struct HOROPTER_API ScheduledFrame {
  virtual ~ScheduledFrame();
  std::int64_t index = 0;              // 0, 1, 2... in capture order
  SteadyClock::time_point captured{};  // when the source delivered it
  std::vector<StageSpan> spans;        // filled by the scheduler
};

// Where frames come from. newFrame() makes an empty frame of the type the
// stages expect; fill() captures into it and returns false at the end of the
// input. fill() may block (a camera waits for its next frame); it throws
// horopter::Error for a device that fails or stalls.
class HOROPTER_API ScheduledSource {
 public:
  virtual ~ScheduledSource();
  virtual std::string name() const = 0;
  virtual std::unique_ptr<ScheduledFrame> newFrame() = 0;
  virtual bool fill(ScheduledFrame& frame) = 0;
};

// One step of the per-frame work.
class HOROPTER_API ScheduledStage {
 public:
  virtual ~ScheduledStage();
  virtual std::string name() const = 0;
  virtual void run(ScheduledFrame& frame) = 0;
};

enum class PipelineMode { Offline, Live };

struct HOROPTER_API SchedulerOptions {
  PipelineMode mode = PipelineMode::Offline;
  int inFlight = 3;             // frames between capture and the end of the last stage, 1..64
  std::int64_t maxFrames = -1;  // stop after this many captured frames (-1: until the end)
  // Polled by the source loop; set it (e.g. from a SIGINT handler) to stop
  // capture and drain the frames in flight.
  const std::atomic<bool>* stopRequested = nullptr;
  // Called on the last lane with every finished frame, in order of completion
  // (capture order in offline mode). Exceptions count as the "output" stage's.
  std::function<void(const ScheduledFrame&)> onFrame;
};

// Throws horopter::Error for options out of range.
HOROPTER_API void validate(const SchedulerOptions& options);

struct HOROPTER_API StageSummary {
  std::string name;
  std::int64_t frames = 0;
  double meanMs = 0;  // wall time per frame in this stage
  double fps() const { return meanMs > 0 ? 1000.0 / meanMs : 0; }
};

struct HOROPTER_API TraceEvent {
  std::string stage;
  std::int64_t frame = 0;
  int lane = 0;                        // 0 = capture, 1.. = the stages, in order
  double startUs = 0, durationUs = 0;  // from the start of the run
};

struct HOROPTER_API RunSummary {
  std::int64_t captured = 0;   // frames the source delivered
  std::int64_t completed = 0;  // frames through every stage
  std::int64_t dropped = 0;    // live mode: stale frames replaced before entering
  double seconds = 0;          // wall time of the run
  double fps() const { return seconds > 0 ? completed / seconds : 0; }
  double meanLatencyMs = 0;  // capture to the end of the last stage
  double maxLatencyMs = 0;
  std::vector<StageSummary> stages;  // "capture" first
  std::vector<TraceEvent> trace;
  bool stoppedByRequest = false;
};

class HOROPTER_API Scheduler {
 public:
  explicit Scheduler(SchedulerOptions options);  // validates them (horopter::Error)
  ~Scheduler();
  Scheduler(const Scheduler&) = delete;
  Scheduler& operator=(const Scheduler&) = delete;

  // Stage names are unique and neither "capture" nor "output".
  Scheduler& add(std::unique_ptr<ScheduledStage> stage);
  const SchedulerOptions& options() const { return options_; }

  // Runs the source through the stages until the source ends, maxFrames are
  // captured or a stop is requested. Throws horopter::Error naming the stage
  // and frame when one fails; every thread is joined either way. With no
  // stage, frames go straight from capture to onFrame.
  RunSummary run(ScheduledSource& source);

 private:
  SchedulerOptions options_;
  std::vector<std::unique_ptr<ScheduledStage>> stages_;
};

// Chrome trace events (open in Perfetto or chrome://tracing): one row per
// lane, one slice per stage and frame, so the overlap of frames is visible.
HOROPTER_API void writeChromeTrace(const RunSummary& summary, const std::string& path);

// The summary as one JSON object: frames, fps, latency_ms, dropped, stages.
HOROPTER_API std::string summaryJson(const RunSummary& summary);

}  // namespace horopter
