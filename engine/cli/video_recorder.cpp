#include "video_recorder.hpp"

#include <opencv2/imgproc.hpp>

#include "horopter/core/error.hpp"

namespace horopter::cli {

namespace {

constexpr std::size_t kQueued = 4;  // views waiting for the encoder, at most

}  // namespace

VideoRecorder::VideoRecorder(std::string path, double fps, int scale)
    : path_(std::move(path)), fps_(fps), scale_(scale) {
  if (scale_ < 1) throw Error("the video's scale must be at least 1");
  thread_ = std::thread([this] { encodeLoop(); });
}

VideoRecorder::~VideoRecorder() {
  try {
    close();
  } catch (...) {  // NOLINT(bugprone-empty-catch): a destructor reports nothing
  }
}

void VideoRecorder::rethrowFailure() {
  if (failure_) std::rethrow_exception(failure_);
}

void VideoRecorder::write(const cv::Mat& view) {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return queue_.size() < kQueued || failure_ || closing_; });
  rethrowFailure();
  if (closing_) throw Error("the video '" + path_ + "' is closed");
  queue_.push_back(view);  // the view is the caller's fresh image: no copy
  changed_.notify_all();
}

void VideoRecorder::encodeLoop() {
  for (;;) {
    cv::Mat view;
    {
      std::unique_lock lock(mutex_);
      changed_.wait(lock, [&] { return !queue_.empty() || closing_; });
      if (queue_.empty()) return;  // closing, and nothing left
      view = std::move(queue_.front());
      queue_.pop_front();
      changed_.notify_all();
    }
    try {
      if (!file_) {
        size_ = cv::Size(view.cols / scale_, view.rows / scale_);
        file_ = std::make_unique<MjpegAviFile>(path_, size_, fps_);
      }
      cv::Mat frame = view;
      if (view.size() != size_) cv::resize(view, frame, size_, 0, 0, cv::INTER_AREA);
      file_->write(frame);
      const std::lock_guard lock(mutex_);
      ++written_;
    } catch (...) {
      const std::lock_guard lock(mutex_);
      failure_ = std::current_exception();
      queue_.clear();
      changed_.notify_all();
      return;
    }
  }
}

void VideoRecorder::close() {
  {
    const std::lock_guard lock(mutex_);
    if (closing_ && !thread_.joinable()) {
      rethrowFailure();
      return;
    }
    closing_ = true;
    changed_.notify_all();
  }
  if (thread_.joinable()) thread_.join();
  rethrowFailure();
  if (file_) file_->close();  // every write of the file is checked there
}

std::int64_t VideoRecorder::framesWritten() const {
  const std::lock_guard lock(mutex_);
  return written_;
}

}  // namespace horopter::cli
