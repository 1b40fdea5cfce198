// The simulator's closed loop; see horopter/sim/closed_loop.hpp.
#include "horopter/sim/closed_loop.hpp"

#include <algorithm>

#include "horopter/app/interaction_stages.hpp"
#include "horopter/core/error.hpp"

namespace horopter::sim {

SyntheticRigHead::SyntheticRigHead(hw::HeadAngles initial, hw::HeadLimits limits, int delay)
    : limits_(limits), delay_(delay), pose_(initial) {
  if (delay < 1)
    throw Error("the actuation delay must be >= 1 frame, got " + std::to_string(delay));
  if (!(limits.panMin <= limits.panMax) || !(limits.tiltMin <= limits.tiltMax))
    throw Error("head limits need min <= max");
}

hw::HeadAngles SyntheticRigHead::clamp(const hw::HeadAngles& a) const {
  hw::HeadAngles c = a;
  c.pan = std::clamp(a.pan, limits_.panMin, limits_.panMax);
  c.tilt = std::clamp(a.tilt, limits_.tiltMin, limits_.tiltMax);
  c.vergence = pose_.vergence;  // the rig keeps its vergence
  return c;
}

void SyntheticRigHead::command(const hw::HeadAngles& target, double) {
  std::lock_guard lock(mutex_);
  liveTarget_ = clamp(target);
}

std::optional<hw::HeadMeasurement> SyntheticRigHead::measured() const {
  std::lock_guard lock(mutex_);
  return hw::HeadMeasurement{hw::Clock::now(), pose_};
}

void SyntheticRigHead::halt() {
  std::lock_guard lock(mutex_);
  liveTarget_.reset();
  pending_.clear();
}

void SyntheticRigHead::post(std::int64_t frame, const std::optional<hw::HeadAngles>& target) {
  {
    std::lock_guard lock(mutex_);
    if (frame <= postedThrough_)
      throw Error("head commands must be posted once per frame, in order: got frame " +
                  std::to_string(frame) + " after " + std::to_string(postedThrough_));
    postedThrough_ = frame;
    if (target) pending_.emplace_back(frame, clamp(*target));
  }
  posted_.notify_all();
}

hw::HeadAngles SyntheticRigHead::poseForFrame(std::int64_t frame,
                                              std::chrono::milliseconds timeout) {
  std::unique_lock lock(mutex_);
  const std::int64_t due = frame - delay_;
  if (!posted_.wait_for(lock, timeout, [&] { return postedThrough_ >= due; }))
    throw Error("the synthetic rig waited " + std::to_string(timeout.count()) +
                " ms for the head command of frame " + std::to_string(due) +
                " (is the head-control stage in the pipeline?)");
  while (!pending_.empty() && pending_.front().first <= due) {
    pose_ = pending_.front().second;
    pending_.pop_front();
  }
  if (liveTarget_) {
    pose_ = *liveTarget_;
    liveTarget_.reset();
  }
  return pose_;
}

ClosedLoopSyntheticSource::ClosedLoopSyntheticSource(const synth::SceneOptions& options, int frames,
                                                     int actuationDelayFrames,
                                                     hw::HeadLimits limits)
    : scene_(options), frames_(frames) {
  if (frames < 1)
    throw Error("the synthetic scene needs at least 1 frame, got " + std::to_string(frames));
  const synth::HeadPose p = options.initialHead;
  head_ = std::make_shared<SyntheticRigHead>(hw::HeadAngles{p.pan, p.tilt, p.vergence}, limits,
                                             actuationDelayFrames);
}

bool ClosedLoopSyntheticSource::next(Frame& frame) {
  if (next_ >= frames_) return false;
  const hw::HeadAngles a = head_->poseForFrame(next_);
  scene_.commandHead({a.pan, a.tilt, a.vergence});
  synth::SyntheticFrame rendered = scene_.render(next_++);
  frame.left = std::move(rendered.left);
  frame.right = std::move(rendered.right);
  // A plain Frame (not from newFrame()) gets the images only.
  if (auto* sim = dynamic_cast<SimFrame*>(&frame)) sim->truth = std::move(rendered.truth);
  return true;
}

CapturePose syntheticCapturePose() {
  return [](const StereoFrame& f) -> std::optional<hw::HeadAngles> {
    const synth::FrameTruth* t = truthOf(f);
    if (!t) return std::nullopt;
    return hw::HeadAngles{t->head.pan, t->head.tilt, t->head.vergence};
  };
}

std::unique_ptr<Stage> makeSyntheticHeadControlStage(HeadControlOptions options,
                                                     ClosedLoopSyntheticSource& source) {
  if (options.actuationDelayFrames != source.head()->actuationDelayFrames())
    throw Error("the head control's actuation delay differs from the synthetic rig's");
  options.focalPx = source.scene().focalPx();
  options.cx = source.scene().cx();
  options.cy = source.scene().cy();
  options.imageHeight = source.scene().options().height;
  options.imageWidth = source.scene().options().width;
  options.framesPerSecond = source.scene().options().framesPerSecond;
  std::shared_ptr<SyntheticRigHead> head = source.head();
  HeadCommandSink sink = [head](std::int64_t frame, const std::optional<hw::HeadAngles>& c) {
    head->post(frame, c);
  };
  return makeHeadControlStage(options, syntheticCapturePose(), sink);
}

}  // namespace horopter::sim
