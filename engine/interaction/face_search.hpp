// The face half of the detection stage: OpenCV's Haar cascade over the zone
// (or the whole image), sized by depth, following the last frame's faces
// between full searches and guided by the zone's skin. Internal to
// engine/interaction; see horopter/interaction/detection.hpp for the options.
#pragma once

#include <opencv2/core.hpp>
#include <opencv2/objdetect.hpp>

#include <cstdint>
#include <vector>

#include "horopter/interaction/detection.hpp"

namespace horopter::detail {

struct FaceSearchResult {
  std::vector<FaceDetection> faces;  // sorted by position (deterministic)
  cv::Size faceSizes;                // widths searched, px (height 0: no upper limit)
  bool fullSearch = true;            // searched the whole region, not only followed faces
};

// Stateful across frames (followed faces, the learnt face width per
// disparity): one per pipeline lane.
class FaceSearch {
 public:
  // Throws horopter::Error for bad face options or a cascade that cannot be
  // loaded.
  explicit FaceSearch(const DetectorOptions& options);

  // Faces in `colour` (frame.left as BGR) within `roi`, the rectangle the
  // detectors cover; `zoneSkin` (roi-sized) is the skin there, inside the
  // zone in the region, and guides the full searches.
  // `options`: those it was made with (the Detector owns them and may move).
  FaceSearchResult find(const DetectorOptions& options, const StereoFrame& frame,
                        const cv::Mat& colour, const cv::Rect& roi, const cv::Mat& zoneSkin);

 private:
  // Face widths the zone's depths allow, pixels.
  struct SizeRange {
    int minPx = 0, maxPx = 0;
    bool valid() const { return minPx > 0 && maxPx >= minPx; }
  };
  struct Followed {
    cv::Rect box;      // where the face was last found
    int missed = 0;    // frames since
    cv::Point2f step;  // its centre's motion between the last two frames that found it, px
  };

  // The cascade over `area` (image coordinates) of the left image (`grey`,
  // or `colour` converted where `grey` is empty) scaled by `scale`, for faces minPx..maxPx wide
  // (full-resolution px; maxPx 0: any); what it finds is appended to
  // `boxes`, in image coordinates.
  void cascadeIn(const DetectorOptions& o, const cv::Mat& colour, const cv::Mat& grey,
                 const cv::Rect& area, int minPx, int maxPx, double scale,
                 std::vector<cv::Rect>& boxes);
  void learnWidthPerDisparity(const StereoFrame& frame, const std::vector<FaceDetection>& faces);
  SizeRange sizesFromDepth(const DetectorOptions& o, const StereoFrame& frame, const cv::Rect& roi);

  cv::CascadeClassifier cascade_;
  cv::Mat grey_, scaled_, labels_, stats_, centroids_;
  std::vector<cv::Rect> found_;  // scratch
  std::vector<Followed> followed_;
  int sinceFullSearch_ = 0;  // frames since the last full search
  int sinceExhaustive_ = 0;  // full searches since the last exhaustive one
  // Face width / disparity (px per px) of the last faces found in the zone.
  std::vector<float> widthPerDisparity_;
  std::size_t nextSample_ = 0;
  int emptySizedSearches_ = 0;        // consecutive full searches sized by depth that found no face
  std::vector<std::int16_t> depths_;  // scratch
};

// The fraction of mask pixels in the central half of a face box.
double zoneCover(const cv::Mat& mask, const cv::Rect& box);

// The median valid disparity (px) in `box` of a CV_16SC1 disparity map
// (1/16 px), sampled every `step` pixels where `mask` (if not empty) is set;
// 0 when none. `scratch` is reused.
double medianDisparity(const cv::Mat& disparity, const cv::Mat& mask, cv::Rect box, int step,
                       std::vector<std::int16_t>& scratch);

}  // namespace horopter::detail
