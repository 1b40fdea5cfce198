// An MJPEG video in an AVI file, from JPEG images the caller encodes:
// libjpeg-turbo (through cv::imencode) encodes a 640x480 view in about a
// third of the instructions of cv::VideoWriter's FFmpeg path (swscale's
// BGR to YUV, then FFmpeg's MJPEG encoder: 33 M against 12.7 M per frame,
// callgrind), and libavformat only muxes. Unlike cv::VideoWriter, every
// write is checked: a full disk is an error naming the file.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

struct AVFormatContext;
struct AVPacket;

namespace horopter::cli {

class MjpegAviFile {
 public:
  // Creates (or truncates) `path` for frames of `size` at `fps` frames/s.
  // Throws horopter::Error naming the path when it cannot.
  MjpegAviFile(const std::string& path, cv::Size size, double fps);
  ~MjpegAviFile();  // closes without its errors; call close() to see them
  MjpegAviFile(const MjpegAviFile&) = delete;
  MjpegAviFile& operator=(const MjpegAviFile&) = delete;

  // Encodes a BGR image of the video's size (quality 90) and appends it.
  void write(const cv::Mat& bgr);
  // Writes the index and closes the file; idempotent. Throws on a failed write.
  void close();
  std::int64_t frames() const { return frames_; }

 private:
  void open(double fps);
  void release();  // frees everything, closes the file without its index
  void check(int status, const char* what) const;

  const std::string path_;
  const cv::Size size_;
  AVFormatContext* context_ = nullptr;
  AVPacket* packet_ = nullptr;
  std::vector<unsigned char> jpeg_;
  std::int64_t frames_ = 0;
  bool open_ = false;
};

}  // namespace horopter::cli
