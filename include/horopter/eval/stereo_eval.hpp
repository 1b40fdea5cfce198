// Accuracy of a disparity map against ground truth, and the same measured for
// cv::StereoBM (the peer) with the same parameters.
#pragma once

#include <optional>
#include <string>

#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

#include "horopter/core/image.hpp"
#include "horopter/kernels/backend.hpp"
#include "horopter/kernels/stereo_params.hpp"

namespace horopter {

// The left band's pixels (StereoParams::leftBand) with known ground truth,
// apart: `reachable` ones, whose true disparity lies within the band's search
// at that column (at most x - r + 0.5 px), and `unreachable` ones, whose
// match is out of the right view's window: any valid output there is wrong.
struct LeftBandScores {
  long reachable = 0, unreachable = 0;
  double reachableBad2 = 0;     // % of reachable with error > 2 px or invalid
  double reachableDensity = 0;  // % of reachable with a valid output
  double falseMatches = 0;      // % of unreachable with a valid output
};

// Percentages are 0..100, over the pixels with known ground truth.
struct StereoScores {
  double bad1 = 0;     // % whose error exceeds 1 px; invalid outputs count as bad
  double bad2 = 0;     // % whose error exceeds 2 px; invalid outputs count as bad
  double avgerr = 0;   // mean |error| in px over the valid outputs
  double density = 0;  // % with a valid output
  double ms = 0;       // wall time per frame (mean over the timed runs)
  std::string backend;
  std::optional<LeftBandScores> leftBand;  // with a left band
};

// Reads an 8- or 16-bit single-channel ground-truth image (palette PNGs
// included) and divides by `scale`: CV_32F pixels, 0 = unknown. A PFM file
// (Middlebury's float disparities in px, recognised by its "Pf"/"PF"
// signature) is read too: its values are divided by `scale` (1 for a PFM in
// px) and inf or NaN become 0 = unknown. Throws
// horopter::Error if the file is missing, unreadable or scale <= 0.
cv::Mat loadGroundTruth(const std::string& path, double scale);

// Reads an image as 8-bit BGR; throws horopter::Error naming the path.
cv::Mat loadColour(const std::string& path, const char* what);
// BGR (or grey) to grey, the one conversion every command uses, so that
// `disparity` and `eval-stereo` see the same pixels.
cv::Mat toGrey(const cv::Mat& image);
// loadColour, then toGrey.
cv::Mat loadGrey(const std::string& path, const char* what);

// Scores a disparity map (S16C1, 1/16 px) with the invalid marker `invalid`
// against ground truth in pixels (CV_32F, <= 0 = unknown).
StereoScores scoreDisparity(const ConstImageView& disparity, std::int16_t invalid,
                            const cv::Mat& groundTruthPx);

// The left band's scores of a disparity map matched with `params`; nullopt
// without a band (params.leftBand 0 or no column left of the region).
std::optional<LeftBandScores> scoreLeftBand(const ConstImageView& disparity,
                                            const StereoParams& params,
                                            const cv::Mat& groundTruthPx);

struct EvalOptions {
  int warmupRuns = 1;
  int timedRuns = 3;
  int threads = 1;  // for Horopter's stripes and for cv::setNumThreads alike
};

// Runs Horopter's front end (prefilter through median) and scores its output.
StereoScores evaluateHoropter(const cv::Mat& left, const cv::Mat& right, const cv::Mat& gtPx,
                              const StereoParams& params, const MedianParams& median,
                              const Backend& backend, const EvalOptions& options = {});

// cv::StereoBM set up with the same parameters (the peer in evals and benches).
// StereoBM has no unfiltered mode: PreFilterType::None maps to its
// normalized-response prefilter. Throws horopter::Error for blockSize < 5,
// which StereoBM does not support.
cv::Ptr<cv::StereoBM> makeOpenCvStereoBM(const StereoParams& params);

// Runs cv::StereoBM with the same parameters (x-Sobel prefilter, texture,
// uniqueness, speckles; its own left-right check) on options.threads threads
// (OpenCV's setting is restored afterwards) and scores its output.
StereoScores evaluateOpenCvStereoBM(const cv::Mat& left, const cv::Mat& right, const cv::Mat& gtPx,
                                    const StereoParams& params, const EvalOptions& options = {});

}  // namespace horopter
