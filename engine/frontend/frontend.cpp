#include "horopter/vision/frontend.hpp"

#include <algorithm>
#include <chrono>
#include <string>
#include <thread>

#include "horopter/core/error.hpp"
#include "horopter/kernels/kernels.hpp"
#include "schedule/thread_pool.hpp"

namespace horopter {

namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

}  // namespace

int resolveThreads(int threads) {
  if (threads == 0) {
    const unsigned hardware = std::thread::hardware_concurrency();
    return static_cast<int>(std::clamp(hardware, 1u, 256u));
  }
  if (threads < 1 || threads > 256)
    throw Error("thread count must be within 1..256, or 0 for every hardware thread, got " +
                std::to_string(threads));
  return threads;
}

StereoFrontend::StereoFrontend(const StereoParams& stereo, const MedianParams& median,
                               const Backend& backend, int threads)
    : stereo_(stereo),
      median_(median),
      backend_(&backend),
      pool_(std::make_unique<ThreadPool>(resolveThreads(threads))) {
  validate(stereo_);
  validate(median_);
}

StereoFrontend::~StereoFrontend() = default;
StereoFrontend::StereoFrontend(StereoFrontend&&) noexcept = default;
StereoFrontend& StereoFrontend::operator=(StereoFrontend&&) noexcept = default;

void StereoFrontend::setStereoParams(const StereoParams& stereo) {
  validate(stereo);
  stereo_ = stereo;
}

int StereoFrontend::threads() const {
  return pool_->threads();
}

void StereoFrontend::allocate(int width, int height) {
  if (clean_.width() == width && clean_.height() == height) return;
  leftFiltered_ = Image(width, height, PixelType::U8C1);
  rightFiltered_ = Image(width, height, PixelType::U8C1);
  texture_ = Image(width, height, PixelType::U8C1);
  clean_ = Image(width, height, PixelType::S16C1);
  winnerRight_ = Image(width, height, PixelType::S16C1);
  median_out_ = Image(width, height, PixelType::S16C1);
  mask_ = Image();
  segmented_ = Image();
}

void StereoFrontend::forEachStripe(int height, const std::function<void(RowRange)>& fn) {
  const int stripes = std::min(pool_->threads(), height);
  pool_->run(stripes, [&](int i) { fn({height * i / stripes, height * (i + 1) / stripes}); });
}

const Image& StereoFrontend::computeDisparity(const ConstImageView& left,
                                              const ConstImageView& right) {
  return computeDisparity(left, right, fullRange(stereo_));
}

const Image& StereoFrontend::computeDisparity(const ConstImageView& left,
                                              const ConstImageView& right, SearchRange range) {
  hasDisparity_ = hasMask_ = false;  // until this frame is through
  checkSearchRange(stereo_, range);
  const StereoParams params = withRange(stereo_, range);
  const BelowRangeGuard guard = guardBelow(stereo_, range);
  checkView(left, PixelType::U8C1, "left image");
  checkView(right, PixelType::U8C1, "right image");
  checkSameSize(left, "left image", right, "right image");
  allocate(left.width, left.height);
  timings_ = {};

  auto start = Clock::now();
  const bool filter = params.preFilterType != PreFilterType::None;
  const bool wantTexture = params.textureThreshold > 0;
  ConstImageView matchLeft = left;
  ConstImageView matchRight = right;
  const int height = left.height;
  if (filter) {
    forEachStripe(height, [&](RowRange rows) {
      prefilter(left, params, leftFiltered_.view(), wantTexture ? texture_.view() : ImageView{},
                *backend_, rows);
      prefilter(right, params, rightFiltered_.view(), {}, *backend_, rows);
    });
    matchLeft = leftFiltered_.view();
    matchRight = rightFiltered_.view();
  } else if (wantTexture) {
    forEachStripe(height, [&](RowRange rows) {
      prefilter(left, params, {}, texture_.view(), *backend_, rows);
    });
  }
  timings_.prefilter = msSince(start);

  start = Clock::now();
  forEachStripe(height, [&](RowRange rows) {
    matchBlocks(matchLeft, matchRight, wantTexture ? texture_.view() : ConstImageView{}, params,
                guard, clean_.view(), winnerRight_.view(), *backend_, rows);
  });
  timings_.match = msSince(start);

  start = Clock::now();
  forEachStripe(height, [&](RowRange rows) {
    leftRightCheck(clean_.view(), winnerRight_.view(), params, *backend_, rows);
  });
  filterSpeckles(clean_.view(), params, *backend_);
  if (range.minDisparity != stereo_.minDisparity)  // another invalid marker
    forEachStripe(
        height, [&](RowRange rows) { restoreInvalidMarker(clean_.view(), stereo_, range, rows); });
  timings_.cleanup = msSince(start);

  if (median_.kernelSize > 0) {
    start = Clock::now();
    forEachStripe(height, [&](RowRange rows) {
      medianFilter(clean_.view(), median_out_.view(), median_, invalidDisparity(stereo_), *backend_,
                   rows);
    });
    timings_.median = msSince(start);
  }
  lastRange_ = range;
  hasDisparity_ = true;
  return disparity();
}

const Image& StereoFrontend::disparity() const {
  return median_.kernelSize > 0 ? median_out_ : clean_;
}

void StereoFrontend::computeMask(std::span<const std::int16_t> thresholds,
                                 const ConstImageView& image) {
  if (!hasDisparity_)
    throw Error(
        "StereoFrontend::computeMask: no disparity: computeDisparity was not called, or its last "
        "call failed");
  hasMask_ = false;
  const auto start = Clock::now();
  const bool segment = !image.empty();
  if (mask_.width() != clean_.width() || mask_.height() != clean_.height())
    mask_ = Image(clean_.width(), clean_.height(), PixelType::U8C1);
  if (segment) {
    checkViewOneOf(image, {PixelType::U8C1, PixelType::U8C3}, "image to segment");
    if (segmented_.width() != image.width || segmented_.height() != image.height ||
        segmented_.type() != image.type)
      segmented_ = Image(image.width, image.height, image.type);
  }
  forEachStripe(clean_.height(), [&](RowRange rows) {
    horopterMask(disparity().view(), thresholds, invalidDisparity(stereo_), mask_.view(), image,
                 segment ? segmented_.view() : ImageView{}, *backend_, rows);
  });
  timings_.mask = msSince(start);
  hasMask_ = true;
}

}  // namespace horopter
