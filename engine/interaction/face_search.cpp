// Haar face search for the detection stage; see face_search.hpp.
#include "face_search.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <tuple>

#include "horopter/core/error.hpp"

namespace horopter::detail {

// The median valid disparity (px) in `box`, where `mask` (if any) is set;
// 0 when none.
double medianDisparity(const cv::Mat& disparity, const cv::Mat& mask, cv::Rect box, int step,
                       std::vector<std::int16_t>& scratch) {
  scratch.clear();
  box &= cv::Rect(0, 0, disparity.cols, disparity.rows);
  for (int y = box.y; y < box.y + box.height; y += step) {
    const auto* row = disparity.ptr<std::int16_t>(y);
    const auto* in = mask.empty() ? nullptr : mask.ptr<std::uint8_t>(y);
    for (int x = box.x; x < box.x + box.width; x += step)
      if (row[x] > 0 && (!in || in[x])) scratch.push_back(row[x]);
  }
  if (scratch.empty()) return 0;
  auto mid = scratch.begin() + static_cast<std::ptrdiff_t>(scratch.size() / 2);
  std::nth_element(scratch.begin(), mid, scratch.end());
  return *mid / 16.0;
}

namespace {

constexpr std::size_t kWidthSamples = 15;  // faces remembered for k
constexpr std::size_t kMinWidthSamples = 3;

}  // namespace

double zoneCover(const cv::Mat& mask, const cv::Rect& box) {
  if (mask.empty()) return 0;
  const cv::Rect centre =
      cv::Rect(box.x + box.width / 4, box.y + box.height / 4, box.width / 2, box.height / 2) &
      cv::Rect(0, 0, mask.cols, mask.rows);
  if (centre.empty()) return 0;
  return cv::countNonZero(mask(centre)) / static_cast<double>(centre.area());
}

FaceSearch::FaceSearch(const DetectorOptions& o) {
  if (!(o.scaleFactor > 1.0 && o.scaleFactor < 2.0))
    throw Error("face scale factor must be in (1, 2), e.g. 1.1");
  // The options of detectorOptions() are checked against it (Detector).
  if (!(o.followMarginFaces >= 0 && o.followMarginFaces <= 10) || !(o.skinGuideArea >= 0))
    throw Error("followMarginFaces must be within 0..10 and skinGuideArea >= 0");
  if (!(o.followSizeRatio == 0 || (o.followSizeRatio >= 1 && o.followSizeRatio <= 4)) ||
      !(o.followSlackFaces >= 0 && o.followSlackFaces <= 10))
    throw Error(
        "followSizeRatio must be 0 (off) or within 1..4, and followSlackFaces within 0..10");
  if (o.followFacePx != 0 && o.followSizeRatio > 0 && o.followFacePx / o.followSizeRatio < 24)
    throw Error(
        "followFacePx over followSizeRatio must be >= 24 (the cascade's window), or followFacePx "
        "0 (off)");
  if (!(o.depthFacePercentiles[0] >= 0 && o.depthFacePercentiles[0] <= o.depthFacePercentiles[1] &&
        o.depthFacePercentiles[1] <= 1) ||
      !(o.depthFaceMargin >= 1))
    throw Error("depth face sizes need percentiles 0 <= far <= near <= 1 and a margin >= 1");
  if (o.depthSizeForgetSearches < 1)
    throw Error("depthSizeForgetSearches must be >= 1 (full searches without a face)");
  if (o.minFacePx != 0 && o.minFacePx < 20)
    throw Error(
        "the smallest face must be >= 20 px (the cascade's window), or 0 for a 16th of the width");
  if (!std::filesystem::exists(o.faceCascade))
    throw Error(
        "face cascade '" + o.faceCascade +
        "' not found: install Debian's opencv-data (scripts/setup.sh) or pass another file");
  if (!cascade_.load(o.faceCascade))
    throw Error("cannot load the face cascade '" + o.faceCascade + "'");
}

// A face's width is k times its disparity (k: the face's width in metres
// over the baseline); each face found in the zone is a sample of k.
void FaceSearch::learnWidthPerDisparity(const StereoFrame& frame,
                                        const std::vector<FaceDetection>& faces) {
  if (frame.disparity.empty() || frame.disparity.type() != CV_16SC1) return;
  for (const FaceDetection& f : faces) {
    if (!f.insideZone) continue;
    const cv::Rect centre(f.box.x + f.box.width / 4, f.box.y + f.box.height / 4, f.box.width / 2,
                          f.box.height / 2);
    const double disparity = medianDisparity(frame.disparity, cv::Mat(), centre, 2, depths_);
    if (!(disparity > 1)) continue;
    const auto k = static_cast<float>(f.width / disparity);
    if (widthPerDisparity_.size() < kWidthSamples)
      widthPerDisparity_.push_back(k);
    else
      widthPerDisparity_[nextSample_++ % kWidthSamples] = k;
  }
}

// The face widths the zone's disparities allow over `roi`, once k is known:
// from the near end of the zone's depths to its far end, with a margin.
FaceSearch::SizeRange FaceSearch::sizesFromDepth(const DetectorOptions& o, const StereoFrame& frame,
                                                 const cv::Rect& roi) {
  if (widthPerDisparity_.size() < kMinWidthSamples || frame.disparity.empty() ||
      frame.disparity.type() != CV_16SC1 || frame.disparity.size() != frame.mask.size())
    return {};
  std::vector<float> ks = widthPerDisparity_;
  std::nth_element(ks.begin(), ks.begin() + static_cast<std::ptrdiff_t>(ks.size() / 2), ks.end());
  const double k = ks[ks.size() / 2];
  // The zone's disparities, sampled every 4th pixel.
  depths_.clear();
  for (int y = roi.y; y < roi.y + roi.height; y += 4) {
    const auto* row = frame.disparity.ptr<std::int16_t>(y);
    const auto* in = frame.mask.ptr<std::uint8_t>(y);
    for (int x = roi.x; x < roi.x + roi.width; x += 4)
      if (row[x] > 0 && in[x]) depths_.push_back(row[x]);
  }
  if (depths_.size() < 16) return {};
  auto at = [&](double q) {
    auto it = depths_.begin() + static_cast<std::ptrdiff_t>(q * (depths_.size() - 1));
    std::nth_element(depths_.begin(), it, depths_.end());
    return *it / 16.0;
  };
  const double far = at(o.depthFacePercentiles[0]), near = at(o.depthFacePercentiles[1]);
  return {static_cast<int>(std::floor(k * far / o.depthFaceMargin)),
          static_cast<int>(std::ceil(k * near * o.depthFaceMargin))};
}

void FaceSearch::cascadeIn(const DetectorOptions& o, const cv::Mat& colour, const cv::Mat& grey,
                           const cv::Rect& area, int minPx, int maxPx, double scale,
                           std::vector<cv::Rect>& boxes) {
  if (area.width < minPx || area.height < minPx) return;
  cv::Mat image;
  if (!grey.empty())
    image = grey(area);
  else {
    cv::cvtColor(colour(area), grey_, cv::COLOR_BGR2GRAY);
    image = grey_;
  }
  if (scale != 1) {
    cv::resize(image, scaled_, cv::Size(), scale, scale, cv::INTER_AREA);
    image = scaled_;
  }
  const int minSize = std::max(20, cvRound(minPx * scale));
  const int maxSize = maxPx > 0 ? std::max(minSize, cvRound(maxPx * scale)) : 0;
  found_.clear();
  cascade_.detectMultiScale(image, found_, o.scaleFactor, o.minNeighbors, 0,
                            cv::Size(minSize, minSize), cv::Size(maxSize, maxSize));
  const double k = 1 / scale;
  for (const cv::Rect& b : found_)
    boxes.emplace_back(cvRound(b.x * k) + area.x, cvRound(b.y * k) + area.y, cvRound(b.width * k),
                       cvRound(b.height * k));
}

FaceSearchResult FaceSearch::find(const DetectorOptions& o, const StereoFrame& frame,
                                  const cv::Mat& colour, const cv::Rect& roi,
                                  const cv::Mat& zoneSkin) {
  const bool region = o.scope == DetectionScope::HoropterRegion;
  const cv::Rect image(0, 0, colour.cols, colour.rows);
  FaceSearchResult result;
  // Faces: the cascade is unsteady on a face at the border of its image, so
  // the region's rectangle gets half the smallest face of margin.
  const int smallestFace = o.minFacePx > 0 ? o.minFacePx : std::max(20, colour.cols / 16);
  int minFace = smallestFace;
  int maxFaceAny = 0;  // 0: no limit
  double scale = std::min(1.0, std::max(o.faceScale, 20.0 / minFace));
  // In the region, the zone's depths bound the faces' sizes (width = k d,
  // k learnt from the faces found so far): fewer pyramid levels. (Scaling
  // the image down to the smallest size allowed was faster still, but the
  // cascade then missed faces: on tuning seed 5009 it lost the face for
  // good.)
  const SizeRange depthSizes =
      region && o.depthFaceSizes ? sizesFromDepth(o, frame, roi) : SizeRange{};
  if (depthSizes.valid()) {
    minFace = std::max(minFace, depthSizes.minPx);
    maxFaceAny = std::max(minFace, depthSizes.maxPx);
  }
  result.faceSizes = cv::Size(minFace, maxFaceAny);
  const int pad = region ? minFace / 2 : 0;
  const cv::Rect faceRoi =
      cv::Rect(roi.x - pad, roi.y - pad, roi.width + 2 * pad, roi.height + 2 * pad) & image;
  // The left image in grey: the rectify stage's (the same conversion, done
  // once per frame) where there is one, else converted window by window.
  const bool haveGrey = frame.leftGrey.size() == colour.size() && frame.leftGrey.type() == CV_8UC1;
  const cv::Mat grey = haveGrey ? frame.leftGrey : cv::Mat();
  std::vector<cv::Rect> boxes;  // image coordinates
  // The cascade over `area` for faces from minFace up to maxFace px wide (0: any).
  auto search = [&](const cv::Rect& area, int maxFace) {
    if (maxFaceAny > 0) maxFace = maxFace > 0 ? std::min(maxFace, maxFaceAny) : maxFaceAny;
    cascadeIn(o, colour, grey, area, minFace, maxFace, scale, boxes);
  };
  // The windows a guided full search looks in: around each skin blob large
  // enough to hold a face (a face is skin; in the region, in the zone).
  auto skinWindows = [&] {
    std::vector<cv::Rect> windows;
    const int n =
        cv::connectedComponentsWithStats(zoneSkin, labels_, stats_, centroids_, 8, CV_32S);
    for (int i = 1; i < n; ++i) {
      const cv::Rect b(stats_.at<int>(i, cv::CC_STAT_LEFT) + roi.x,
                       stats_.at<int>(i, cv::CC_STAT_TOP) + roi.y,
                       stats_.at<int>(i, cv::CC_STAT_WIDTH), stats_.at<int>(i, cv::CC_STAT_HEIGHT));
      if (stats_.at<int>(i, cv::CC_STAT_AREA) < o.skinGuideArea * minFace * minFace ||
          std::max(b.width, b.height) < minFace / 2)
        continue;
      const int g = std::max(minFace, std::max(b.width, b.height)) / 2 + pad;
      windows.push_back(cv::Rect(b.x - g, b.y - g, b.width + 2 * g, b.height + 2 * g) & faceRoi);
    }
    return windows;
  };
  // Windows close together overlap: keep one box of each face.
  auto dedupe = [&] {
    std::sort(boxes.begin(), boxes.end(), [](const cv::Rect& a, const cv::Rect& b) {
      return std::tie(a.x, a.y, a.width, a.height) < std::tie(b.x, b.y, b.width, b.height);
    });
    std::vector<cv::Rect> unique;
    for (const cv::Rect& b : boxes) {
      const bool seen = std::any_of(unique.begin(), unique.end(), [&](const cv::Rect& u) {
        return (u & b).area() * 2 > std::min(u.area(), b.area());
      });
      if (!seen) unique.push_back(b);
    }
    boxes = std::move(unique);
  };
  // Whether a box the cascade found is kept (the region keeps the zone's).
  auto kept = [&](const cv::Rect& b) {
    return !region || zoneCover(frame.mask, b) >= o.faceZoneCover;
  };
  const bool follow = !followed_.empty() && sinceFullSearch_ + 1 < o.fullSearchEvery;
  bool searchAll = !follow;
  if (follow) {
    ++sinceFullSearch_;
    for (const Followed& followed : followed_) {
      const cv::Rect& f = followed.box;
      if (o.followSizeRatio > 0) {
        // Where its last step takes it, with a margin for a change of step,
        // at about its own size.
        const double margin = std::min(o.followMarginFaces * f.width,
                                       o.followSlackFaces * f.width + cv::norm(followed.step));
        const int g = cvRound(margin);
        const cv::Rect window(f.x + cvRound(followed.step.x) - g,
                              f.y + cvRound(followed.step.y) - g, f.width + 2 * g,
                              f.height + 2 * g);
        const int lo = std::max(smallestFace, cvFloor(f.width / o.followSizeRatio));
        // The image scaled so the face is about followFacePx wide: the
        // cascade steps its window by 1 px instead of 2 on pyramid levels
        // over twice its 24 px, four times the windows for a near face.
        const double followScale =
            o.followFacePx > 0 ? std::min(scale, o.followFacePx / f.width) : scale;
        cascadeIn(o, colour, grey, window & faceRoi, lo,
                  std::max(lo, cvCeil(f.width * o.followSizeRatio)), followScale, boxes);
      } else {
        const int g = cvRound(o.followMarginFaces * f.width);
        search(cv::Rect(f.x - g, f.y - g, f.width + 2 * g, f.height + 2 * g) & faceRoi,
               2 * f.width);
      }
    }
    dedupe();
    // followMissFrames 0: a followed face not found again makes this frame
    // search everywhere after all.
    if (o.followMissFrames == 0 && static_cast<std::size_t>(std::count_if(
                                       boxes.begin(), boxes.end(), kept)) < followed_.size()) {
      boxes.clear();
      searchAll = true;
    }
  }
  if (searchAll) {
    sinceFullSearch_ = 0;
    // While a face is followed, guided by skin, but every
    // exhaustiveSearchEvery-th full search looks everywhere (a face the skin
    // model misses); with no face yet, everywhere (a face found a frame
    // late is elected a frame late).
    const bool guided =
        region && o.exhaustiveSearchEvery != 1 && !followed_.empty() &&
        (o.exhaustiveSearchEvery == 0 || ++sinceExhaustive_ < o.exhaustiveSearchEvery);
    if (guided) {
      for (const cv::Rect& w : skinWindows())
        search(w, 0);
      dedupe();
    } else {
      sinceExhaustive_ = 0;
      search(faceRoi, 0);
    }
  }
  result.fullSearch = searchAll;
  for (const cv::Rect& b : boxes) {
    FaceDetection f;
    f.box = b;
    f.centre = cv::Point2f(b.x + 0.5f * b.width, b.y + 0.5f * b.height);
    f.width = static_cast<float>(b.width);
    f.insideZone = zoneCover(frame.mask, b) >= o.faceZoneCover;
    if (!kept(b)) continue;  // the region holds the zone only
    result.faces.push_back(f);
  }
  if (region && o.depthFaceSizes) learnWidthPerDisparity(frame, result.faces);
  // k learnt from faces that were not faces (a false detection in the zone)
  // bounds the sizes away from the real one, which is then never found
  // (tuning seeds 10033 and 10048: never elected). Full searches sized by depth that
  // keep finding nothing forget k, and search every size until it is learnt
  // again.
  if (searchAll && depthSizes.valid()) {
    emptySizedSearches_ = result.faces.empty() ? emptySizedSearches_ + 1 : 0;
    if (emptySizedSearches_ >= o.depthSizeForgetSearches) {
      widthPerDisparity_.clear();
      nextSample_ = 0;
      emptySizedSearches_ = 0;
    }
  }
  // Followed next frame: the faces found, and those not found again for at
  // most followMissFrames frames (the cascade misses a face now and then; a
  // miss then costs no full search).
  // A face found again carries its step since (the motion its next window
  // expects).
  std::vector<Followed> next;
  auto centreOf = [](const cv::Rect& b) {
    return cv::Point2f(b.x + 0.5f * b.width, b.y + 0.5f * b.height);
  };
  auto sameFace = [&](const FaceDetection& g, const Followed& f) {
    return cv::norm(g.centre - centreOf(f.box)) <
           std::max(g.width, static_cast<float>(f.box.width));
  };
  for (const FaceDetection& g : result.faces) {
    auto before = std::find_if(followed_.begin(), followed_.end(),
                               [&](const Followed& f) { return f.missed == 0 && sameFace(g, f); });
    next.push_back(
        {g.box, 0, before == followed_.end() ? cv::Point2f() : g.centre - centreOf(before->box)});
  }
  for (const Followed& f : followed_) {
    const bool foundAgain = std::any_of(result.faces.begin(), result.faces.end(),
                                        [&](const FaceDetection& g) { return sameFace(g, f); });
    if (!foundAgain && f.missed < o.followMissFrames) next.push_back({f.box, f.missed + 1, f.step});
  }
  followed_ = std::move(next);
  std::sort(
      result.faces.begin(), result.faces.end(), [](const FaceDetection& a, const FaceDetection& b) {
        return std::tie(a.box.x, a.box.y, a.box.width) < std::tie(b.box.x, b.box.y, b.box.width);
      });

  return result;
}

}  // namespace horopter::detail
