// A FIFO of frames between two lanes of the pipeline. It needs no capacity:
// the pipeline's in-flight slots bound how many frames exist at all.
#pragma once

#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>

#include "horopter/pipeline/scheduler.hpp"

namespace horopter::pipeline_detail {

class FrameQueue {
 public:
  void push(std::unique_ptr<ScheduledFrame> frame) {
    {
      std::lock_guard lock(mutex_);
      frames_.push_back(std::move(frame));
    }
    ready_.notify_one();
  }

  // The next frame, or nullptr once the queue is closed and empty.
  std::unique_ptr<ScheduledFrame> pop() {
    std::unique_lock lock(mutex_);
    ready_.wait(lock, [&] { return closed_ || !frames_.empty(); });
    if (frames_.empty()) return nullptr;
    auto frame = std::move(frames_.front());
    frames_.pop_front();
    return frame;
  }

  // No more frames will come; pop() returns what is left, then nullptr.
  void close() {
    {
      std::lock_guard lock(mutex_);
      closed_ = true;
    }
    ready_.notify_all();
  }

 private:
  std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<std::unique_ptr<ScheduledFrame>> frames_;
  bool closed_ = false;
};

}  // namespace horopter::pipeline_detail
