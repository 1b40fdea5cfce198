// Capture sources that read files (internal; open them with openSource).
#pragma once

#include <filesystem>
#include <opencv2/videoio.hpp>
#include <string>
#include <vector>

#include "horopter/vision/capture.hpp"

namespace horopter::capture {

// A folder of left/right images, paired by name (left0007.png with
// right0007.png, or left/0007.png with right/0007.png), in natural order
// of the names (frame2 before frame10).
class DirectorySource : public StereoSource {
 public:
  explicit DirectorySource(const std::string& dir);
  std::string name() const override { return "dir:" + dir_; }
  bool next(StereoFrame& frame) override;

 private:
  std::string dir_;
  std::vector<std::filesystem::path> left_, right_;
  std::size_t next_ = 0;
};

// Two video files read frame by frame; they must end together.
class VideoPairSource : public StereoSource {
 public:
  VideoPairSource(const std::string& leftPath, const std::string& rightPath);
  std::string name() const override { return "video"; }
  bool next(StereoFrame& frame) override;

 private:
  std::string leftPath_, rightPath_;
  cv::VideoCapture left_, right_;
  std::int64_t frames_ = 0;
};

}  // namespace horopter::capture
