// Following a hand by its look where stereo is blind. Left of x = d (the
// hand's disparity) the right camera does not see it, and nearer than the
// search range it has no disparity: no zone there, so the detector finds
// nothing, though the left image still shows the hand. The tracker then
// looks for the hand's last patch seen with stereo around its prediction.
// Internal to engine/interaction; see horopter/interaction/tracking.hpp for the options.
#pragma once

#include <opencv2/core.hpp>

#include <optional>

namespace horopter::detail {

// The fraction of valid (positive) disparities of a CV_16SC1 map within
// `halfPx` of `at` (0 where the window is outside the map).
double validDisparityFraction(const cv::Mat& disparity, cv::Point2f at, int halfPx);

// One hand's appearance: a square grey patch, kept from the last frame the
// hand was detected in.
class PatchFollower;

// Whether what `follower`'s look matches at `at` now is new there: the look
// matches nothing within `radiusPx` of `at` in `before` (the image of its
// last detection) by `minScore`. Skin-coloured clutter matches the look
// wherever it stands, before as now; a hand that left for the band was not
// there yet. True where `before` is empty.
bool appearedSince(const PatchFollower& follower, const cv::Mat& before, cv::Point2f at,
                   int radiusPx, double minScore);

class PatchFollower {
 public:
  // Keeps the patch of `grey` (CV_8UC1) centred on `at`, `sidePx` across;
  // forgets it where the patch is not wholly inside the image.
  void remember(const cv::Mat& grey, cv::Point2f at, int sidePx);
  void forget() { patch_.release(); }
  bool empty() const { return patch_.empty(); }
  // The centre of the best match (normalised cross-correlation) of the patch
  // in `grey` among the centres within `searchPx` of the box spanned by `a`
  // and `b` (the prediction and where the hand was last seen: a fast hand
  // that stops outruns its prediction), if it scores at least `minScore`;
  // nothing without a patch or where the window leaves no room.
  std::optional<cv::Point2f> find(const cv::Mat& grey, cv::Point2f a, cv::Point2f b, int searchPx,
                                  double minScore) const;

  // The centre of the best match of the patch among the centres in
  // `centres` (clipped where the patch would leave the image) whose mean
  // grey level is within a quarter of the patch's and whose deviation is
  // within a factor 1.5 of it, if it scores at least `minScore`; nothing
  // without a patch or room.
  std::optional<cv::Point2f> findAlikeIn(const cv::Mat& grey, cv::Rect centres,
                                         double minScore) const;

 private:
  cv::Mat patch_;
};

}  // namespace horopter::detail
