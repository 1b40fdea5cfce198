// Following a hand by its look; see blind_follow.hpp.
#include "blind_follow.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace horopter::detail {

namespace {
constexpr double kMinDeviation = 2.0;  // grey levels
// A match found far from the track must also look like the hand in level
// and contrast, which normalised cross-correlation ignores: without this,
// searches of the band held hand tracks for 9-19 frames on static matches
// at the image's lower left (tuning seeds 10352-10365).
constexpr double kAlikeMeanFraction = 0.25;
constexpr double kAlikeDeviationRatio = 1.5;
}  // namespace

double validDisparityFraction(const cv::Mat& disparity, cv::Point2f at, int halfPx) {
  if (disparity.empty() || disparity.type() != CV_16SC1) return 0;
  const cv::Rect window =
      cv::Rect(cvRound(at.x) - halfPx, cvRound(at.y) - halfPx, 2 * halfPx + 1, 2 * halfPx + 1) &
      cv::Rect(0, 0, disparity.cols, disparity.rows);
  if (window.empty()) return 0;
  int valid = 0;
  for (int y = window.y; y < window.y + window.height; ++y) {
    const auto* row = disparity.ptr<std::int16_t>(y);
    for (int x = window.x; x < window.x + window.width; ++x)
      valid += row[x] > 0;
  }
  return static_cast<double>(valid) / window.area();
}

void PatchFollower::remember(const cv::Mat& grey, cv::Point2f at, int sidePx) {
  const cv::Rect box(cvRound(at.x) - sidePx / 2, cvRound(at.y) - sidePx / 2, sidePx, sidePx);
  if (grey.empty() || grey.type() != CV_8UC1 || sidePx < 3 ||
      (box & cv::Rect(0, 0, grey.cols, grey.rows)) != box) {
    patch_.release();
    return;
  }
  // A flat patch correlates with anything (or nothing): not a look.
  cv::Scalar mean, deviation;
  cv::meanStdDev(grey(box), mean, deviation);
  if (deviation[0] < kMinDeviation) {
    patch_.release();
    return;
  }
  grey(box).copyTo(patch_);
}

std::optional<cv::Point2f> PatchFollower::find(const cv::Mat& grey, cv::Point2f a, cv::Point2f b,
                                               int searchPx, double minScore) const {
  if (patch_.empty() || grey.empty() || grey.type() != CV_8UC1) return std::nullopt;
  const int side = patch_.cols;
  const int x0 = cvRound(std::min(a.x, b.x)), x1 = cvRound(std::max(a.x, b.x));
  const int y0 = cvRound(std::min(a.y, b.y)), y1 = cvRound(std::max(a.y, b.y));
  const cv::Rect window = cv::Rect(x0 - side / 2 - searchPx, y0 - side / 2 - searchPx,
                                   x1 - x0 + side + 2 * searchPx, y1 - y0 + side + 2 * searchPx) &
                          cv::Rect(0, 0, grey.cols, grey.rows);
  if (window.width < side || window.height < side) return std::nullopt;
  cv::Mat score;
  cv::matchTemplate(grey(window), patch_, score, cv::TM_CCOEFF_NORMED);
  double best = 0;
  cv::Point where;
  cv::minMaxLoc(score, nullptr, &best, nullptr, &where);
  if (!(best >= minScore)) return std::nullopt;
  return cv::Point2f(static_cast<float>(window.x + where.x + side / 2),
                     static_cast<float>(window.y + where.y + side / 2));
}

std::optional<cv::Point2f> PatchFollower::findAlikeIn(const cv::Mat& grey, cv::Rect centres,
                                                      double minScore) const {
  if (patch_.empty() || grey.empty() || grey.type() != CV_8UC1 || centres.empty())
    return std::nullopt;
  const int side = patch_.cols;
  const cv::Rect window = cv::Rect(centres.x - side / 2, centres.y - side / 2,
                                   centres.width + side - 1, centres.height + side - 1) &
                          cv::Rect(0, 0, grey.cols, grey.rows);
  if (window.width < side || window.height < side) return std::nullopt;
  cv::Mat score;
  cv::matchTemplate(grey(window), patch_, score, cv::TM_CCOEFF_NORMED);
  // Each placement's mean and deviation (box means anchored at the
  // placement's corner, as matchTemplate's score is).
  cv::Mat level, square;
  cv::Mat window32;
  grey(window).convertTo(window32, CV_32F);
  cv::boxFilter(window32, level, CV_32F, cv::Size(side, side), cv::Point(0, 0));
  cv::boxFilter(window32.mul(window32), square, CV_32F, cv::Size(side, side), cv::Point(0, 0));
  cv::Scalar patchMean, patchDeviation;
  cv::meanStdDev(patch_, patchMean, patchDeviation);
  double best = -2;
  cv::Point where;
  for (int y = 0; y < score.rows; ++y)
    for (int x = 0; x < score.cols; ++x) {
      const double s = score.at<float>(y, x);
      if (!(s > best)) continue;
      const double mean = level.at<float>(y, x);
      const double deviation = std::sqrt(std::max(0.0, square.at<float>(y, x) - mean * mean));
      if (std::abs(mean - patchMean[0]) > kAlikeMeanFraction * patchMean[0] ||
          deviation > kAlikeDeviationRatio * patchDeviation[0] ||
          deviation * kAlikeDeviationRatio < patchDeviation[0])
        continue;
      best = s;
      where = {x, y};
    }
  if (!(best >= minScore)) return std::nullopt;
  return cv::Point2f(static_cast<float>(window.x + where.x + side / 2),
                     static_cast<float>(window.y + where.y + side / 2));
}

bool appearedSince(const PatchFollower& follower, const cv::Mat& before, cv::Point2f at,
                   int radiusPx, double minScore) {
  return before.empty() || !follower.find(before, at, at, radiusPx, minScore);
}

}  // namespace horopter::detail
