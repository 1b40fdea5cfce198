// run.avi, encoded on its own thread: `horopter run` hands each annotated
// view over and goes on, so the encoder (about half of the video's CPU,
// drawing the view the other half) is off the pipeline's last lane and
// uses the CPU the lanes leave idle. The queue is bounded: when the encoder
// falls behind, the pipeline waits rather than lose a frame.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <exception>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include <opencv2/core.hpp>

#include "mjpeg_avi.hpp"

namespace horopter::cli {

class VideoRecorder {
 public:
  // `scale` divides the views' width and height in the video (1: as drawn).
  VideoRecorder(std::string path, double fps, int scale);
  ~VideoRecorder();  // close() without its errors
  VideoRecorder(const VideoRecorder&) = delete;
  VideoRecorder& operator=(const VideoRecorder&) = delete;

  // Queues a view (BGR). The video's size is the first view's (divided by
  // the scale); a later view of another size is resized to it, so that no
  // frame is dropped. Throws horopter::Error for the encoder's failure.
  void write(const cv::Mat& view);
  // Encodes what is queued and closes the file, every write checked (a
  // failed one is an error naming the file). Idempotent.
  void close();
  std::int64_t framesWritten() const;

 private:
  void encodeLoop();
  void rethrowFailure();

  const std::string path_;
  const double fps_;
  const int scale_;
  std::unique_ptr<MjpegAviFile> file_;  // opened at the first view
  cv::Size size_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<cv::Mat> queue_;
  bool closing_ = false;
  std::exception_ptr failure_;
  std::int64_t written_ = 0;
  std::thread thread_;
};

}  // namespace horopter::cli
