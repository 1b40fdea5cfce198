// V4L2 cameras through OpenCV's VideoCapture (CAP_V4L2).
#include "capture/camera_sources.hpp"

#include <cmath>
#include <filesystem>

#include "horopter/core/error.hpp"

namespace horopter::capture {

namespace {

std::chrono::milliseconds millis(double ms) {
  return std::chrono::milliseconds(static_cast<long long>(std::ceil(ms)));
}

}  // namespace

CameraReader::CameraReader(const std::string& device, const CaptureOptions& options)
    : device_(device) {
  if (!std::filesystem::exists(device))
    throw Error("camera '" + device + "' does not exist: list cameras with `ls /dev/video*`");
  if (!capture_.open(device, cv::CAP_V4L2))
    throw Error(
        "cannot open camera '" + device +
        "' with V4L2: is it a capture device, and is it free (not used by another program)?");
  if (options.width > 0) capture_.set(cv::CAP_PROP_FRAME_WIDTH, options.width);
  if (options.height > 0) capture_.set(cv::CAP_PROP_FRAME_HEIGHT, options.height);
  if (options.fps > 0) capture_.set(cv::CAP_PROP_FPS, options.fps);
  thread_ = std::thread([this] { loop(); });
}

CameraReader::~CameraReader() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
}

void CameraReader::loop() {
  while (!stop_) {
    cv::Mat image;
    if (!capture_.read(image) || image.empty()) {
      std::lock_guard lock(mutex_);
      failure_ = "camera '" + device_ + "' stopped delivering frames (unplugged or failed)";
      arrived_.notify_all();
      return;
    }
    std::lock_guard lock(mutex_);
    latest_.image = std::move(image);
    latest_.time = SteadyClock::now();
    ++latest_.sequence;
    arrived_.notify_all();
  }
}

CameraReader::Shot CameraReader::newerThan(std::int64_t after, std::chrono::milliseconds timeout) {
  std::unique_lock lock(mutex_);
  const bool got = arrived_.wait_for(lock, timeout,
                                     [&] { return latest_.sequence > after || !failure_.empty(); });
  if (!failure_.empty()) throw Error(failure_);
  if (!got)
    throw Error("camera '" + device_ + "' delivered no frame for " +
                std::to_string(timeout.count()) + " ms: it stalled");
  return latest_;
}

CameraPairSource::CameraPairSource(const std::string& leftDevice, const std::string& rightDevice,
                                   const CaptureOptions& options)
    : options_(options), left_(leftDevice, options), right_(rightDevice, options) {
  if (!(options.maxSkewMs > 0)) throw Error("the maximum skew between the cameras must be > 0 ms");
}

bool CameraPairSource::next(StereoFrame& frame) {
  const auto timeout = millis(options_.stallTimeoutMs);
  const auto skew = std::chrono::duration<double, std::milli>(options_.maxSkewMs);
  CameraReader::Shot l = left_.newerThan(lastLeft_, timeout);
  CameraReader::Shot r = right_.newerThan(lastRight_, timeout);
  // The older of the two waits for its camera's next frame until they pair.
  for (int tries = 0; std::chrono::abs(l.time - r.time) > skew; ++tries) {
    if (tries > 100)
      throw Error("cameras '" + left_.device() + "' and '" + right_.device() +
                  "' never deliver frames within " + std::to_string(options_.maxSkewMs) +
                  " ms of each other: are they running at the same rate?");
    ++drops_;
    if (l.time < r.time)
      l = left_.newerThan(l.sequence, timeout);
    else
      r = right_.newerThan(r.sequence, timeout);
  }
  lastLeft_ = l.sequence;
  lastRight_ = r.sequence;
  if (l.image.size() != r.image.size())
    throw Error("cameras deliver " + std::to_string(l.image.cols) + "x" +
                std::to_string(l.image.rows) + " and " + std::to_string(r.image.cols) + "x" +
                std::to_string(r.image.rows) + ": set one size with --size WxH");
  frame.left = l.image;
  frame.right = r.image;
  return true;
}

SideBySideSource::SideBySideSource(const std::string& device, const CaptureOptions& options)
    : options_(options), camera_(device, options) {}

bool SideBySideSource::next(StereoFrame& frame) {
  const CameraReader::Shot shot = camera_.newerThan(last_, millis(options_.stallTimeoutMs));
  last_ = shot.sequence;
  if (shot.image.cols % 2 != 0)
    throw Error("side-by-side camera image is " + std::to_string(shot.image.cols) +
                " pixels wide: an odd width cannot be split into two views");
  const int half = shot.image.cols / 2;
  frame.left = shot.image.colRange(0, half).clone();
  frame.right = shot.image.colRange(half, shot.image.cols).clone();
  return true;
}

}  // namespace horopter::capture
