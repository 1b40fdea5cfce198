// Live camera sources (internal; open them with openSource).
#pragma once

#include <atomic>
#include <condition_variable>
#include <mutex>
#include <opencv2/videoio.hpp>
#include <string>
#include <thread>

#include "horopter/vision/capture.hpp"

namespace horopter::capture {

// One V4L2 camera read continuously on its own thread, so a slow consumer
// never stalls the driver: it keeps the newest frame with its timestamp.
class CameraReader {
 public:
  CameraReader(const std::string& device, const CaptureOptions& options);
  ~CameraReader();
  CameraReader(const CameraReader&) = delete;
  CameraReader& operator=(const CameraReader&) = delete;

  struct Shot {
    cv::Mat image;
    SteadyClock::time_point time{};
    std::int64_t sequence = 0;  // 1, 2, ... per frame the camera delivered
  };
  // The newest frame newer than `after` (a sequence number), waiting up to
  // `timeout`; throws horopter::Error if the camera stalled or died.
  Shot newerThan(std::int64_t after, std::chrono::milliseconds timeout);
  const std::string& device() const { return device_; }

 private:
  void loop();

  std::string device_;
  cv::VideoCapture capture_;
  std::thread thread_;
  std::mutex mutex_;
  std::condition_variable arrived_;
  Shot latest_;
  std::string failure_;
  std::atomic<bool> stop_{false};
};

// Two cameras whose frames are paired by timestamp, within maxSkewMs; frames
// that find no partner are counted as dropped.
class CameraPairSource : public StereoSource {
 public:
  CameraPairSource(const std::string& leftDevice, const std::string& rightDevice,
                   const CaptureOptions& options);
  std::string name() const override { return "camera"; }
  bool next(StereoFrame& frame) override;
  std::int64_t unpairedDrops() const { return drops_; }

 private:
  CaptureOptions options_;
  CameraReader left_, right_;
  std::int64_t lastLeft_ = 0, lastRight_ = 0, drops_ = 0;
};

// One camera delivering both views side by side in one image.
class SideBySideSource : public StereoSource {
 public:
  SideBySideSource(const std::string& device, const CaptureOptions& options);
  std::string name() const override { return "sbs"; }
  bool next(StereoFrame& frame) override;

 private:
  CaptureOptions options_;
  CameraReader camera_;
  std::int64_t last_ = 0;
};

}  // namespace horopter::capture
