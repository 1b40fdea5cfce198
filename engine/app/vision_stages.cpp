// The front end's pipeline stages. Each stage's output is copied into the
// frame: the front end reuses its buffers for the next frame while this one
// is still in flight downstream.
#include "horopter/app/vision_stages.hpp"

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <string>

#include "horopter/core/error.hpp"
#include "horopter/kernels/kernels.hpp"
#include "horopter/vision/frontend.hpp"
#include "horopter/vision/geometry.hpp"
#include "horopter/vision/opencl_frontend.hpp"
#include "horopter/vision/opencv.hpp"

namespace horopter {

namespace {

cv::Mat toGreyMat(const cv::Mat& image) {
  if (image.empty()) throw Error("the frame has no image (the source delivered an empty one)");
  if (image.type() == CV_8UC1) return image;
  cv::Mat grey;
  if (image.type() == CV_8UC3)
    cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  else if (image.type() == CV_8UC4)
    cv::cvtColor(image, grey, cv::COLOR_BGRA2GRAY);
  else
    throw Error("captured images must be 8-bit grey, BGR or BGRA");
  return grey;
}

class RectifyStage final : public Stage {
 public:
  RectifyStage(RectifyFunction rectify, ThresholdFunction thresholds)
      : rectify_(std::move(rectify)), thresholds_(std::move(thresholds)) {}
  std::string name() const override { return "rectify"; }
  void process(Frame& f) override {
    if (f.left.size() != f.right.size()) throw Error("left and right images differ in size");
    if (rectify_) {
      cv::Mat l, r;
      rectify_(f.left, f.right, l, r);
      f.left = l;
      f.right = r;
    }
    f.leftGrey = toGreyMat(f.left);
    f.rightGrey = toGreyMat(f.right);
    if (!thresholds_) return;
    f.thresholds.assign(static_cast<std::size_t>(f.leftGrey.cols), 0);
    thresholds_(f, f.thresholds);
    if (f.thresholds.size() != static_cast<std::size_t>(f.leftGrey.cols))
      throw Error("the threshold function gave " + std::to_string(f.thresholds.size()) +
                  " thresholds for " + std::to_string(f.leftGrey.cols) + " columns");
  }

 private:
  RectifyFunction rectify_;
  ThresholdFunction thresholds_;
};

// The frame's search range: the zone's when zone search is on.
SearchRange searchRangeOf(const Frame& f, const StereoParams& stereo, const ZoneSearch& zone) {
  if (!zone.enabled) return fullRange(stereo);
  if (f.thresholds.empty())
    throw Error(
        "zone search needs the zone's thresholds before the disparity (the rectify "
        "stage's threshold function)");
  return zoneSearchRange(stereo, f.thresholds, zone);
}

class DisparityStage final : public Stage {
 public:
  DisparityStage(const StereoParams& stereo, const MedianParams& median, const Backend& backend,
                 int threads, const ZoneSearch& zone)
      : frontend_(stereo, median, backend, threads), zone_(zone) {
    validate(zone_, stereo);
  }
  std::string name() const override { return "disparity"; }
  void process(Frame& f) override {
    if (f.leftGrey.empty()) throw Error("no grey views: put the rectify stage before disparity");
    f.searchRange = searchRangeOf(f, frontend_.stereoParams(), zone_);
    const Image& d =
        frontend_.computeDisparity(viewOf(f.leftGrey), viewOf(f.rightGrey), f.searchRange);
    f.disparity = matOf(d).clone();
  }

 private:
  StereoFrontend frontend_;
  ZoneSearch zone_;
};

// On an OpenCL device the whole chain stays on the device (one upload of
// the pair, one download of the disparity; the speckle filter on the CPU),
// instead of one round trip per kernel through the backend's kernel table.
// The lane sleeps in the wait while the device works, so the other stages'
// lanes keep the CPU busy with the neighbouring frames.
class OpenClDisparityStage final : public Stage {
 public:
  OpenClDisparityStage(const StereoParams& stereo, const MedianParams& median,
                       const std::string& device, int cpuThreads, const ZoneSearch& zone)
      : frontend_(stereo, median, device, 1, cpuThreads), stereo_(stereo), zone_(zone) {
    validate(zone_, stereo);
  }
  std::string name() const override { return "disparity"; }
  void process(Frame& f) override {
    if (f.leftGrey.empty()) throw Error("no grey views: put the rectify stage before disparity");
    f.searchRange = searchRangeOf(f, stereo_, zone_);
    const Image& d =
        frontend_.computeDisparity(viewOf(f.leftGrey), viewOf(f.rightGrey), f.searchRange);
    f.disparity = matOf(d).clone();
  }

 private:
  OpenClFrontend frontend_;
  StereoParams stereo_;
  ZoneSearch zone_;
};

class MaskStage final : public Stage {
 public:
  MaskStage(const StereoParams& stereo, const Backend& backend)
      : invalid_(invalidDisparity(stereo)), backend_(backend) {}
  std::string name() const override { return "mask"; }
  void process(Frame& f) override {
    if (f.disparity.empty()) throw Error("no disparity: put the disparity stage before mask");
    if (f.thresholds.size() != static_cast<std::size_t>(f.disparity.cols))
      throw Error("the mask needs one threshold per column (" + std::to_string(f.disparity.cols) +
                  "), the frame has " + std::to_string(f.thresholds.size()) +
                  ": give the rectify stage a threshold function");
    f.mask.create(f.disparity.size(), CV_8UC1);
    horopterMask(viewOf(f.disparity), f.thresholds, invalid_, mutableViewOf(f.mask), {}, {},
                 backend_);
  }

 private:
  std::int16_t invalid_;
  const Backend& backend_;
};

}  // namespace

std::unique_ptr<Stage> makeRectifyStage(RectifyFunction rectify, ThresholdFunction thresholds) {
  return std::make_unique<RectifyStage>(std::move(rectify), std::move(thresholds));
}

std::unique_ptr<Stage> makeDisparityStage(const StereoParams& stereo, const MedianParams& median,
                                          const Backend& backend, int threads,
                                          const ZoneSearch& zone) {
  if (backend.name.rfind("opencl", 0) == 0)
    return std::make_unique<OpenClDisparityStage>(stereo, median, backend.name, threads, zone);
  return std::make_unique<DisparityStage>(stereo, median, backend, threads, zone);
}

std::unique_ptr<Stage> makeMaskStage(const StereoParams& stereo, const Backend& backend) {
  return std::make_unique<MaskStage>(stereo, backend);
}

ThresholdFunction fixationDisparityThresholds(const StereoParams& stereo,
                                              std::optional<double> fixationDisparityPx,
                                              std::optional<double> focalPx) {
  const double fixation =
      fixationDisparityPx.value_or(stereo.minDisparity + stereo.numDisparities / 2.0);
  if (!(fixation > 0 && std::isfinite(fixation)))
    throw Error("the fixation disparity must be a positive number of pixels, got " +
                std::to_string(fixation) +
                (fixationDisparityPx ? "" : " (the middle of the search range)") +
                ": give the fixation point's disparity on the centre column");
  if (focalPx && !(*focalPx > 0 && std::isfinite(*focalPx)))
    throw Error("the focal length must be a positive number of pixels");
  return [fixation, focalPx](const Frame& f, std::vector<std::int16_t>& out) {
    RectifiedGeometry g;
    g.focalPx = focalPx.value_or(f.leftGrey.cols);
    g.cx = (f.leftGrey.cols - 1) / 2.0;
    g.cy = (f.leftGrey.rows - 1) / 2.0;
    g.baseline = 1.0;  // thresholds in pixels do not depend on the unit
    out = horopterThresholds(g, f.leftGrey.cols, fixationFromDisparity(g, g.cx, fixation));
  };
}

}  // namespace horopter
