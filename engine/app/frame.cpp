// The application's frame on the generic scheduler: the typed Stage and
// FrameSource, makeStage, frameSourceOf, Pipeline.
#include "horopter/app/frame.hpp"

#include <utility>

#include "horopter/core/error.hpp"

namespace horopter {

namespace {

class FunctionStage final : public Stage {
 public:
  FunctionStage(std::string name, std::function<void(Frame&)> fn)
      : name_(std::move(name)), fn_(std::move(fn)) {}
  std::string name() const override { return name_; }
  void process(Frame& frame) override { fn_(frame); }

 private:
  std::string name_;
  std::function<void(Frame&)> fn_;
};

class CapturedFrames final : public FrameSource {
 public:
  explicit CapturedFrames(std::unique_ptr<StereoSource> source) : source_(std::move(source)) {}
  std::string name() const override { return source_->name(); }
  bool next(Frame& frame) override { return source_->next(frame); }

 private:
  std::unique_ptr<StereoSource> source_;
};

SchedulerOptions schedulerOptions(const PipelineOptions& o) {
  SchedulerOptions s;
  s.mode = o.mode;
  s.inFlight = o.inFlight;
  s.maxFrames = o.maxFrames;
  s.stopRequested = o.stopRequested;
  if (o.onFrame)
    // Every frame comes from a FrameSource's newFrame(): a Frame.
    s.onFrame = [onFrame = o.onFrame](const ScheduledFrame& f) {
      onFrame(static_cast<const Frame&>(f));
    };
  return s;
}

}  // namespace

// The scheduler only runs frames that a FrameSource made, so each is a Frame.
void Stage::run(ScheduledFrame& frame) {
  process(static_cast<Frame&>(frame));
}

std::unique_ptr<ScheduledFrame> FrameSource::newFrame() {
  return std::make_unique<Frame>();
}

bool FrameSource::fill(ScheduledFrame& frame) {
  return next(static_cast<Frame&>(frame));
}

std::unique_ptr<Stage> makeStage(std::string name, std::function<void(Frame&)> fn) {
  if (name.empty()) throw Error("a pipeline stage needs a name");
  if (!fn) throw Error("pipeline stage '" + name + "' has no function");
  return std::make_unique<FunctionStage>(std::move(name), std::move(fn));
}

std::unique_ptr<FrameSource> frameSourceOf(std::unique_ptr<StereoSource> source) {
  if (!source) throw Error("frameSourceOf: no source");
  return std::make_unique<CapturedFrames>(std::move(source));
}

Pipeline::Pipeline(PipelineOptions options)
    : options_(std::move(options)), scheduler_(schedulerOptions(options_)) {}

Pipeline& Pipeline::add(std::unique_ptr<Stage> stage) {
  scheduler_.add(std::move(stage));
  return *this;
}

RunSummary Pipeline::run(FrameSource& source) {
  return scheduler_.run(source);
}

}  // namespace horopter
