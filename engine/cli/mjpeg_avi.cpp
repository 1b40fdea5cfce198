#include "mjpeg_avi.hpp"

#include <sstream>

#include <opencv2/imgcodecs.hpp>

extern "C" {
#include <libavformat/avformat.h>
#include <libavutil/error.h>
#include <libavutil/pixfmt.h>
}

#include "horopter/core/error.hpp"

namespace horopter::cli {

namespace {

constexpr int kJpegQuality = 90;

std::string ffmpegMessage(int status) {
  char text[AV_ERROR_MAX_STRING_SIZE] = {};
  av_strerror(status, text, sizeof text);
  return text;
}

}  // namespace

MjpegAviFile::MjpegAviFile(const std::string& path, cv::Size size, double fps)
    : path_(path), size_(size) {
  if (size.width <= 0 || size.height <= 0 || size.width > 65535 || size.height > 65535)
    throw Error("the video '" + path + "' cannot have a frame size of " +
                std::to_string(size.width) + "x" + std::to_string(size.height));
  if (!(fps > 0 && fps <= 1000)) throw Error("the video '" + path + "' needs 0 < fps <= 1000");
  try {
    open(fps);
  } catch (...) {
    release();
    throw;
  }
}

void MjpegAviFile::open(double fps) {
  check(avformat_alloc_output_context2(&context_, nullptr, "avi", path_.c_str()), "cannot create");
  AVStream* stream = avformat_new_stream(context_, nullptr);
  packet_ = av_packet_alloc();
  if (stream == nullptr || packet_ == nullptr)
    throw Error("cannot create the video '" + path_ + "': out of memory");
  AVCodecParameters& codec = *stream->codecpar;
  codec.codec_type = AVMEDIA_TYPE_VIDEO;
  codec.codec_id = AV_CODEC_ID_MJPEG;
  codec.width = size_.width;
  codec.height = size_.height;
  codec.format = AV_PIX_FMT_YUVJ420P;  // what libjpeg-turbo writes from BGR by default
  stream->avg_frame_rate = av_d2q(fps, 100000);
  stream->time_base = av_inv_q(stream->avg_frame_rate);
  check(avio_open(&context_->pb, path_.c_str(), AVIO_FLAG_WRITE), "cannot create");
  check(avformat_write_header(context_, nullptr), "cannot write the header of");
  open_ = true;
}

void MjpegAviFile::release() {
  if (context_ != nullptr) avio_closep(&context_->pb);  // no-op when not opened
  av_packet_free(&packet_);
  avformat_free_context(context_);
  context_ = nullptr;
}

MjpegAviFile::~MjpegAviFile() {
  try {
    close();
  } catch (...) {  // NOLINT(bugprone-empty-catch): a destructor reports nothing
  }
}

void MjpegAviFile::check(int status, const char* what) const {
  if (status >= 0) return;
  std::ostringstream message;
  message << what << " the video '" << path_ << "': " << ffmpegMessage(status);
  throw Error(message.str());
}

void MjpegAviFile::write(const cv::Mat& bgr) {
  if (!open_) throw Error("the video '" + path_ + "' is closed");
  if (bgr.type() != CV_8UC3 || bgr.size() != size_)
    throw Error("a frame for the video '" + path_ + "' is not a BGR image of its size");
  if (!cv::imencode(".jpg", bgr, jpeg_, {cv::IMWRITE_JPEG_QUALITY, kJpegQuality}))
    throw Error("cannot encode a frame of the video '" + path_ + "'");
  AVStream* stream = context_->streams[0];
  packet_->data = jpeg_.data();
  packet_->size = static_cast<int>(jpeg_.size());
  packet_->stream_index = 0;
  packet_->flags = AV_PKT_FLAG_KEY;
  packet_->pts = packet_->dts =
      av_rescale_q(frames_, av_inv_q(stream->avg_frame_rate), stream->time_base);
  packet_->duration = av_rescale_q(1, av_inv_q(stream->avg_frame_rate), stream->time_base);
  const int status = av_write_frame(context_, packet_);
  packet_->data = nullptr;  // the buffer is ours, not the packet's
  packet_->size = 0;
  check(status, "cannot write a frame of");
  check(context_->pb->error, "cannot write a frame of");
  ++frames_;
}

void MjpegAviFile::close() {
  int status = 0;
  const char* failed = nullptr;
  if (open_) {
    open_ = false;
    status = av_write_trailer(context_);
    if (status < 0) failed = "cannot write the index of";
    const int closed = avio_closep(&context_->pb);
    if (failed == nullptr && closed < 0) {
      status = closed;
      failed = "cannot close";
    }
  }
  release();
  if (failed != nullptr) check(status, failed);
}

}  // namespace horopter::cli
