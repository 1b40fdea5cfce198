// The scheduler: order and determinism offline, dropping in live mode, error
// propagation, stop requests, back-pressure, and the overlap of frames.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <fstream>
#include <mutex>
#include <sstream>
#include <thread>

#include "horopter/app/frame.hpp"
#include "horopter/core/error.hpp"

namespace horopter {
namespace {

using namespace std::chrono_literals;

// Frames carrying a number; optionally paced (a camera at a given rate).
class CountingSource : public FrameSource {
 public:
  explicit CountingSource(std::int64_t count, std::chrono::microseconds period = 0us)
      : count_(count), period_(period) {}
  std::string name() const override { return "counting"; }
  bool next(Frame& frame) override {
    if (produced_ == count_) return false;
    if (period_ > 0us) std::this_thread::sleep_for(period_);
    frame.left = cv::Mat(1, 1, CV_32SC1, cv::Scalar(static_cast<int>(produced_)));
    ++produced_;
    return true;
  }

 private:
  std::int64_t count_, produced_ = 0;
  std::chrono::microseconds period_;
};

// A stage with state that depends on every earlier frame (like a tracker):
// out = in * 3 + running sum of earlier outputs, modulo a prime.
std::unique_ptr<Stage> statefulStage(const std::string& name, std::chrono::microseconds work) {
  auto sum = std::make_shared<std::int64_t>(0);
  return makeStage(name, [sum, work](Frame& f) {
    if (work > 0us) std::this_thread::sleep_for(work);
    const std::int64_t in = f.left.at<int>(0, 0);
    const std::int64_t out = (in * 3 + *sum) % 1000003;
    *sum = (*sum + out) % 1000003;
    f.left.at<int>(0, 0) = static_cast<int>(out);
  });
}

std::vector<int> runAndCollect(PipelineOptions options, std::int64_t frames,
                               std::chrono::microseconds work) {
  std::vector<int> outputs;
  options.onFrame = [&](const Frame& f) { outputs.push_back(f.left.at<int>(0, 0)); };
  Pipeline pipeline(options);
  pipeline.add(statefulStage("a", work))
      .add(statefulStage("b", work / 2))
      .add(statefulStage("c", 0us));
  CountingSource source(frames);
  const RunSummary summary = pipeline.run(source);
  EXPECT_EQ(summary.captured, frames);
  EXPECT_EQ(summary.completed, frames);
  EXPECT_EQ(summary.dropped, 0);
  return outputs;
}

TEST(Pipeline, OfflineOutputsDoNotDependOnFramesInFlight) {
  PipelineOptions options;
  options.inFlight = 1;
  const auto reference = runAndCollect(options, 40, 200us);
  ASSERT_EQ(reference.size(), 40u);
  for (int inFlight : {2, 3, 8}) {
    options.inFlight = inFlight;
    EXPECT_EQ(runAndCollect(options, 40, 200us), reference) << inFlight << " frames in flight";
  }
}

TEST(Pipeline, FramesComeOutInCaptureOrder) {
  PipelineOptions options;
  options.inFlight = 4;
  std::vector<std::int64_t> order;
  options.onFrame = [&](const Frame& f) { order.push_back(f.index); };
  Pipeline pipeline(options);
  pipeline.add(makeStage("jitter", [](Frame& f) {
    std::this_thread::sleep_for(std::chrono::microseconds(100 * (f.index % 3)));
  }));
  CountingSource source(30);
  pipeline.run(source);
  ASSERT_EQ(order.size(), 30u);
  for (std::size_t i = 0; i < order.size(); ++i)
    EXPECT_EQ(order[i], static_cast<std::int64_t>(i));
}

TEST(Pipeline, NeverMoreFramesInFlightThanAllowed) {
  for (int inFlight : {1, 2, 3}) {
    PipelineOptions options;
    options.inFlight = inFlight;
    std::atomic<int> alive{0}, most{0};
    // Counts frames from the first stage to the end of the last.
    options.onFrame = [&](const Frame&) { --alive; };
    Pipeline pipeline(options);
    pipeline.add(makeStage("enter", [&](Frame&) {
      const int now = ++alive;
      int seen = most.load();
      while (now > seen && !most.compare_exchange_weak(seen, now)) {
      }
    }));
    pipeline.add(makeStage("slow", [](Frame&) { std::this_thread::sleep_for(300us); }));
    CountingSource source(30);
    pipeline.run(source);
    EXPECT_LE(most.load(), inFlight);
    if (inFlight > 1) {
      EXPECT_GT(most.load(), 1) << "frames never overlapped";
    }
  }
}

// Offline, capture counts as being in flight: with one frame in flight the
// source is never asked for a frame while another is in a stage; with two,
// the next capture runs beside the stage. Checked with flags, not timing.
TEST(Pipeline, OfflineCaptureTakesAnInFlightSlot) {
  for (int inFlight : {1, 2}) {
    std::atomic<bool> inStage{false}, captureDuringStage{false};
    class WatchingSource : public CountingSource {
     public:
      WatchingSource(std::atomic<bool>& stage, std::atomic<bool>& seen)
          : CountingSource(12, 500us), stage_(stage), seen_(seen) {}
      bool next(Frame& frame) override {
        if (stage_) seen_ = true;
        const bool got = CountingSource::next(frame);
        if (stage_) seen_ = true;
        return got;
      }

     private:
      std::atomic<bool>& stage_;
      std::atomic<bool>& seen_;
    } source(inStage, captureDuringStage);
    PipelineOptions options;
    options.inFlight = inFlight;
    Pipeline pipeline(options);
    pipeline.add(makeStage("work", [&](Frame&) {
      inStage = true;
      std::this_thread::sleep_for(2ms);
      inStage = false;
    }));
    const RunSummary s = pipeline.run(source);
    EXPECT_EQ(s.completed, 12);
    if (inFlight == 1)
      EXPECT_FALSE(captureDuringStage) << "one in flight must be one frame at a time";
    else
      EXPECT_TRUE(captureDuringStage) << "two in flight: capture never overlapped the stage";
  }
}

TEST(Pipeline, SeveralFramesInFlightOverlapStages) {
  // Two stages of 2 ms each: one frame at a time takes about 4 ms a frame,
  // three in flight about 2 ms. Checked from the trace, not from timing:
  // with three in flight, some frame's "a" runs while another's "b" does.
  PipelineOptions options;
  options.inFlight = 3;
  Pipeline pipeline(options);
  pipeline.add(makeStage("a", [](Frame&) { std::this_thread::sleep_for(2ms); }));
  pipeline.add(makeStage("b", [](Frame&) { std::this_thread::sleep_for(2ms); }));
  CountingSource source(10);
  const RunSummary s = pipeline.run(source);
  bool overlap = false;
  for (const auto& x : s.trace)
    for (const auto& y : s.trace)
      if (x.stage == "a" && y.stage == "b" && x.frame != y.frame &&
          x.startUs < y.startUs + y.durationUs && y.startUs < x.startUs + x.durationUs)
        overlap = true;
  EXPECT_TRUE(overlap);
  ASSERT_EQ(s.stages.size(), 3u);
  EXPECT_EQ(s.stages[1].name, "a");
  EXPECT_EQ(s.stages[1].frames, 10);
  EXPECT_GE(s.stages[1].meanMs, 1.9);
}

TEST(Pipeline, LiveModeDropsStaleFramesAndKeepsTheNewest) {
  // A camera at 1 frame / ms into a stage that needs 5 ms: most frames are
  // stale by the time a slot frees, and the last captured one still gets in.
  PipelineOptions options;
  options.mode = PipelineMode::Live;
  options.inFlight = 1;
  std::vector<std::int64_t> seen;
  options.onFrame = [&](const Frame& f) { seen.push_back(f.index); };
  Pipeline pipeline(options);
  pipeline.add(makeStage("slow", [](Frame&) { std::this_thread::sleep_for(5ms); }));
  CountingSource source(60, 1000us);
  const RunSummary s = pipeline.run(source);
  EXPECT_EQ(s.captured, 60);
  EXPECT_GT(s.dropped, s.captured / 4);
  EXPECT_EQ(s.completed + s.dropped, s.captured);
  ASSERT_FALSE(seen.empty());
  EXPECT_EQ(seen.back(), 59);
  for (std::size_t i = 1; i < seen.size(); ++i)
    EXPECT_LT(seen[i - 1], seen[i]);
  // Latency stays near one frame's work, not the backlog of 60 frames.
  EXPECT_LT(s.meanLatencyMs, 60.0);
}

TEST(Pipeline, OfflineModeNeverDrops) {
  PipelineOptions options;
  options.inFlight = 1;
  Pipeline pipeline(options);
  pipeline.add(makeStage("slow", [](Frame&) { std::this_thread::sleep_for(1ms); }));
  CountingSource source(20);
  const RunSummary s = pipeline.run(source);
  EXPECT_EQ(s.completed, 20);
  EXPECT_EQ(s.dropped, 0);
}

TEST(Pipeline, AFailingStageStopsTheRunAndNamesStageAndFrame) {
  for (int inFlight : {1, 3}) {
    PipelineOptions options;
    options.inFlight = inFlight;
    std::atomic<int> afterFailure{0};
    Pipeline pipeline(options);
    pipeline.add(makeStage("fine", [](Frame&) {}));
    pipeline.add(makeStage("detector", [](Frame& f) {
      if (f.index == 7) throw Error("cascade file unreadable");
    }));
    pipeline.add(makeStage("after", [&](Frame& f) {
      if (f.index >= 7) ++afterFailure;
    }));
    CountingSource source(1000);
    try {
      pipeline.run(source);
      FAIL() << "no error";
    } catch (const Error& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("'detector'"), std::string::npos) << what;
      EXPECT_NE(what.find("frame 7"), std::string::npos) << what;
      EXPECT_NE(what.find("cascade file unreadable"), std::string::npos) << what;
    }
    EXPECT_EQ(afterFailure.load(), 0);
  }
}

TEST(Pipeline, AFailingSourceIsReportedAsCapture) {
  class DyingCamera : public FrameSource {
   public:
    std::string name() const override { return "camera"; }
    bool next(Frame& f) override {
      if (n_ == 3) throw Error("camera /dev/video0 stopped delivering frames");
      f.left = cv::Mat(1, 1, CV_32SC1, cv::Scalar(n_++));
      return true;
    }

   private:
    int n_ = 0;
  };
  Pipeline pipeline(PipelineOptions{});
  pipeline.add(makeStage("work", [](Frame&) {}));
  DyingCamera camera;
  try {
    pipeline.run(camera);
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("'capture'"), std::string::npos) << what;
    EXPECT_NE(what.find("frame 3"), std::string::npos) << what;
  }
}

TEST(Pipeline, AFailingOutputCallbackStopsTheRun) {
  PipelineOptions options;
  options.onFrame = [](const Frame& f) {
    if (f.index == 2) throw Error("disk full");
  };
  Pipeline pipeline(options);
  CountingSource source(100);
  EXPECT_THROW(pipeline.run(source), Error);
}

TEST(Pipeline, AStopRequestDrainsTheFramesInFlight) {
  std::atomic<bool> stop{false};
  PipelineOptions options;
  options.inFlight = 3;
  options.stopRequested = &stop;
  std::int64_t finished = 0;
  options.onFrame = [&](const Frame& f) {
    ++finished;
    if (f.index == 5) stop = true;
  };
  Pipeline pipeline(options);
  pipeline.add(makeStage("work", [](Frame&) { std::this_thread::sleep_for(200us); }));
  CountingSource source(1000);
  const RunSummary s = pipeline.run(source);
  EXPECT_TRUE(s.stoppedByRequest);
  EXPECT_LT(s.captured, 1000);
  EXPECT_EQ(s.completed, s.captured);  // nothing captured is lost
  EXPECT_EQ(finished, s.completed);
}

TEST(Pipeline, MaxFramesStopsCapture) {
  PipelineOptions options;
  options.maxFrames = 12;
  Pipeline pipeline(options);
  CountingSource source(100);
  const RunSummary s = pipeline.run(source);
  EXPECT_EQ(s.captured, 12);
  EXPECT_EQ(s.completed, 12);
}

TEST(Pipeline, BadOptionsAndStagesAreClearErrors) {
  PipelineOptions options;
  options.inFlight = 0;
  EXPECT_THROW(Pipeline{options}, Error);
  options.inFlight = 65;
  EXPECT_THROW(Pipeline{options}, Error);
  Pipeline pipeline(PipelineOptions{});
  EXPECT_THROW(pipeline.add(nullptr), Error);
  EXPECT_THROW(makeStage("", [](Frame&) {}), Error);
  pipeline.add(makeStage("x", [](Frame&) {}));
  EXPECT_THROW(pipeline.add(makeStage("x", [](Frame&) {})), Error);
  EXPECT_THROW(pipeline.add(makeStage("capture", [](Frame&) {})), Error);
}

TEST(Pipeline, TraceAndSummaryAreJson) {
  PipelineOptions options;
  Pipeline pipeline(options);
  pipeline.add(makeStage("disparity", [](Frame&) {}));
  CountingSource source(4);
  const RunSummary s = pipeline.run(source);
  EXPECT_EQ(s.trace.size(), 8u);  // capture + disparity per frame
  const auto json = nlohmann::json::parse(summaryJson(s));
  EXPECT_EQ(json.at("frames"), 4);
  EXPECT_TRUE(json.at("fps").is_number());
  EXPECT_TRUE(json.at("latency_ms").is_number());
  EXPECT_EQ(json.at("stages").at("disparity").at("frames"), 4);
  // Not finite (nothing timed): null, not the invalid bare nan of printf.
  RunSummary empty;
  empty.meanLatencyMs = std::nan("");
  empty.maxLatencyMs = std::numeric_limits<double>::infinity();
  const auto none = nlohmann::json::parse(summaryJson(empty));
  EXPECT_TRUE(none.at("latency_ms").is_null());
  EXPECT_TRUE(none.at("max_latency_ms").is_null());
  EXPECT_EQ(none.at("fps"), 0);
  const std::string path = ::testing::TempDir() + "/horopter_trace.json";
  writeChromeTrace(s, path);
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  const auto trace = nlohmann::json::parse(text.str());
  EXPECT_EQ(trace.at("displayTimeUnit"), "ms");
  // Lane names (capture, disparity) and one event per stage per frame.
  ASSERT_EQ(trace.at("traceEvents").size(), 2u + 8u);
  EXPECT_EQ(trace.at("traceEvents").back().at("name"), "disparity #3");
  // One event per line, between the opening and the closing line.
  text.clear();
  text.seekg(0);
  std::string line;
  int lines = 0;
  while (std::getline(text, line))
    ++lines;
  EXPECT_EQ(lines, 2 + 10);
  EXPECT_THROW(writeChromeTrace(s, "/nonexistent-dir/trace.json"), Error);
}

}  // namespace
}  // namespace horopter
