#include "horopter/eval/stereo_eval.hpp"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "horopter/core/error.hpp"
#include "horopter/kernels/kernels.hpp"
#include "horopter/vision/frontend.hpp"
#include "horopter/vision/opencv.hpp"
#include "io/disparity_images.hpp"
#include "io/image_files.hpp"

namespace horopter {

namespace {

void requireFile(const std::string& path, const char* what) {
  if (!std::filesystem::is_regular_file(path))
    throw Error(std::string(what) + " '" + path + "' does not exist or is not a file");
}

// Times `run` (after warm-up runs) and returns the mean milliseconds.
template <typename Fn>
double timeRuns(const EvalOptions& options, Fn&& run) {
  for (int i = 0; i < options.warmupRuns; ++i)
    run();
  const int runs = std::max(1, options.timedRuns);
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < runs; ++i)
    run();
  const std::chrono::duration<double, std::milli> elapsed =
      std::chrono::steady_clock::now() - start;
  return elapsed.count() / runs;
}

void checkPair(const cv::Mat& left, const cv::Mat& right, const cv::Mat& gtPx) {
  if (left.size() != right.size())
    throw Error("left and right images differ in size: rectify them to one size");
  if (gtPx.size() != left.size())
    throw Error("ground truth is " + std::to_string(gtPx.cols) + "x" + std::to_string(gtPx.rows) +
                " but the images are " + std::to_string(left.cols) + "x" +
                std::to_string(left.rows));
}

}  // namespace

cv::Mat loadColour(const std::string& path, const char* what) {
  requireFile(path, what);
  cv::Mat colour = readImage(path, cv::IMREAD_COLOR);
  if (colour.empty()) throw Error(std::string(what) + " '" + path + "' could not be decoded");
  return colour;
}

cv::Mat toGrey(const cv::Mat& image) {
  if (image.type() == CV_8UC1) return image;
  if (image.type() != CV_8UC3)
    throw Error("expected an 8-bit grey or BGR image, got " + cv::typeToString(image.type()));
  cv::Mat grey;
  cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  return grey;
}

cv::Mat loadGrey(const std::string& path, const char* what) {
  return toGrey(loadColour(path, what));
}

cv::Mat loadGroundTruth(const std::string& path, double scale) {
  if (!(scale > 0))
    throw Error("ground-truth scale must be positive, got " + std::to_string(scale));
  requireFile(path, "ground truth");
  if (isPfmFile(path)) {
    // Middlebury's float ground truth, in px: inf (or NaN) = unknown.
    cv::Mat px = readPfm(path);
    for (int y = 0; y < px.rows; ++y) {
      auto* p = px.ptr<float>(y);
      for (int x = 0; x < px.cols; ++x)
        p[x] = std::isfinite(p[x]) ? static_cast<float>(p[x] / scale) : 0.0f;
    }
    return px;
  }
  const cv::Mat raw = readImage(path, cv::IMREAD_GRAYSCALE | cv::IMREAD_ANYDEPTH);
  if (raw.empty()) throw Error("ground truth '" + path + "' could not be decoded");
  if (raw.depth() != CV_8U && raw.depth() != CV_16U)
    throw Error("ground truth '" + path + "' must be 8- or 16-bit");
  cv::Mat px;
  raw.convertTo(px, CV_32F, 1.0 / scale);
  return px;
}

StereoScores scoreDisparity(const ConstImageView& disparity, std::int16_t invalid,
                            const cv::Mat& groundTruthPx) {
  checkView(disparity, PixelType::S16C1, "disparity");
  if (groundTruthPx.type() != CV_32FC1 || groundTruthPx.cols != disparity.width ||
      groundTruthPx.rows != disparity.height)
    throw Error("ground truth must be CV_32FC1 of the disparity's size");
  long known = 0, valid = 0, bad1 = 0, bad2 = 0;
  double errorSum = 0;
  for (int y = 0; y < disparity.height; ++y) {
    const auto* d = disparity.row<std::int16_t>(y);
    const auto* gt = groundTruthPx.ptr<float>(y);
    for (int x = 0; x < disparity.width; ++x) {
      if (!(gt[x] > 0)) continue;
      ++known;
      if (d[x] == invalid) {
        ++bad1;
        ++bad2;
        continue;
      }
      ++valid;
      const double error = std::abs(d[x] / static_cast<double>(kDisparityScale) - gt[x]);
      errorSum += error;
      bad1 += error > 1.0;
      bad2 += error > 2.0;
    }
  }
  StereoScores s;
  if (known == 0) throw Error("ground truth has no known pixel (all zero)");
  s.bad1 = 100.0 * bad1 / known;
  s.bad2 = 100.0 * bad2 / known;
  s.density = 100.0 * valid / known;
  s.avgerr = valid > 0 ? errorSum / valid : 0.0;
  return s;
}

std::optional<LeftBandScores> scoreLeftBand(const ConstImageView& disparity,
                                            const StereoParams& params,
                                            const cv::Mat& groundTruthPx) {
  const MatchRegion region = matchRegion(disparity.width, disparity.height, params);
  if (region.empty() || region.bandX0 >= region.x0) return std::nullopt;
  const std::int16_t invalid = invalidDisparity(params);
  const int r = params.blockSize / 2;
  LeftBandScores s;
  long reachableBad2 = 0, reachableValid = 0, falseMatches = 0;
  for (int y = region.y0; y < region.y1; ++y) {
    const auto* d = disparity.row<std::int16_t>(y);
    const auto* gt = groundTruthPx.ptr<float>(y);
    for (int x = region.bandX0; x < region.x0; ++x) {
      if (!(gt[x] > 0)) continue;
      const bool valid = d[x] != invalid;
      if (gt[x] > x - r + 0.5) {
        ++s.unreachable;
        falseMatches += valid;
        continue;
      }
      ++s.reachable;
      reachableValid += valid;
      reachableBad2 += !valid || std::abs(d[x] / double{kDisparityScale} - gt[x]) > 2.0;
    }
  }
  const auto percent = [](long part, long whole) { return whole > 0 ? 100.0 * part / whole : 0.0; };
  s.reachableBad2 = percent(reachableBad2, s.reachable);
  s.reachableDensity = percent(reachableValid, s.reachable);
  s.falseMatches = percent(falseMatches, s.unreachable);
  return s;
}

StereoScores evaluateHoropter(const cv::Mat& left, const cv::Mat& right, const cv::Mat& gtPx,
                              const StereoParams& params, const MedianParams& median,
                              const Backend& backend, const EvalOptions& options) {
  checkPair(left, right, gtPx);
  StereoFrontend frontend(params, median, backend, options.threads);
  const double ms =
      timeRuns(options, [&] { frontend.computeDisparity(viewOf(left), viewOf(right)); });
  StereoScores s = scoreDisparity(frontend.disparity().view(), invalidDisparity(params), gtPx);
  s.leftBand = scoreLeftBand(frontend.disparity().view(), params, gtPx);
  s.ms = ms;
  s.backend = backend.name;
  return s;
}

cv::Ptr<cv::StereoBM> makeOpenCvStereoBM(const StereoParams& params) {
  validate(params);
  if (params.blockSize < 5)
    throw Error("cv::StereoBM needs blockSize >= 5, got " + std::to_string(params.blockSize));
  auto bm = cv::StereoBM::create(params.numDisparities, params.blockSize);
  bm->setMinDisparity(params.minDisparity);
  bm->setPreFilterType(params.preFilterType == PreFilterType::XSobel
                           ? cv::StereoBM::PREFILTER_XSOBEL
                           : cv::StereoBM::PREFILTER_NORMALIZED_RESPONSE);
  bm->setPreFilterSize(params.preFilterSize);
  bm->setPreFilterCap(params.preFilterCap);
  bm->setTextureThreshold(params.textureThreshold);
  bm->setUniquenessRatio(params.uniquenessRatio);
  bm->setDisp12MaxDiff(params.disp12MaxDiff);
  bm->setSpeckleWindowSize(params.speckleWindowSize);
  bm->setSpeckleRange(params.speckleRange);
  return bm;
}

StereoScores evaluateOpenCvStereoBM(const cv::Mat& left, const cv::Mat& right, const cv::Mat& gtPx,
                                    const StereoParams& params, const EvalOptions& options) {
  checkPair(left, right, gtPx);
  const cv::Ptr<cv::StereoBM> bm = makeOpenCvStereoBM(params);
  cv::Mat disparity;
  const int previousThreads = cv::getNumThreads();
  cv::setNumThreads(options.threads);
  double ms = 0;
  try {
    ms = timeRuns(options, [&] { bm->compute(left, right, disparity); });
  } catch (...) {
    cv::setNumThreads(previousThreads);
    throw;
  }
  cv::setNumThreads(previousThreads);
  StereoScores s = scoreDisparity(viewOf(disparity), invalidDisparity(params), gtPx);
  s.ms = ms;
  s.backend = "opencv-stereobm";
  return s;
}

}  // namespace horopter
