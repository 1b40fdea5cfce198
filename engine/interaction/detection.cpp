// Face and hand detection inside the zone or over the whole image; see
// horopter/detection.hpp.
#include "horopter/detection.hpp"

#include <opencv2/imgproc.hpp>
#include <opencv2/objdetect.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "horopter/error.hpp"

namespace horopter {

const char* detectionScopeName(DetectionScope scope) {
  return scope == DetectionScope::HoropterRegion ? "horopter-region" : "full-image";
}

namespace {
// Face widths the zone's depths allow, pixels.
struct FaceSizeRange {
  int minPx = 0, maxPx = 0;
  bool valid() const { return minPx > 0 && maxPx >= minPx; }
};

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

constexpr std::size_t kWidthSamples = 15;  // faces remembered for k
constexpr std::size_t kMinWidthSamples = 3;

}  // namespace

struct Detector::Impl {
  cv::CascadeClassifier cascade;
  cv::Mat grey, skin, grown, labels, stats, centroids, distance;
  cv::Mat openKernel, closeKernel, maskCloseKernel, erodeKernel;
  struct Followed {
    cv::Rect box;    // where the face was last found
    int missed = 0;  // frames since
  };
  std::vector<Followed> followed;
  int sinceFullSearch = 0;  // frames since the last full search
  int sinceExhaustive = 0;  // full searches since the last exhaustive one
  // Face width / disparity (px per px) of the last faces found in the zone.
  std::vector<float> widthPerDisparity;
  std::size_t nextSample = 0;
  std::vector<std::int16_t> depths;  // scratch

  // A face's width is k times its disparity (k: the face's width in metres
  // over the baseline); each face found in the zone is a sample of k.
  void learnFaceWidthPerDisparity(const Frame& frame, const std::vector<FaceDetection>& faces) {
    if (frame.disparity.empty() || frame.disparity.type() != CV_16SC1) return;
    for (const FaceDetection& f : faces) {
      if (!f.insideZone) continue;
      const cv::Rect centre(f.box.x + f.box.width / 4, f.box.y + f.box.height / 4, f.box.width / 2,
                            f.box.height / 2);
      const double disparity = medianDisparity(frame.disparity, cv::Mat(), centre, 2, depths);
      if (!(disparity > 1)) continue;
      const auto k = static_cast<float>(f.width / disparity);
      if (widthPerDisparity.size() < kWidthSamples)
        widthPerDisparity.push_back(k);
      else
        widthPerDisparity[nextSample++ % kWidthSamples] = k;
    }
  }

  // The face widths the zone's disparities allow over `roi`, once k is known:
  // from the near end of the zone's depths to its far end, with a margin.
  FaceSizeRange faceSizesFromDepth(const Frame& frame, const cv::Rect& roi,
                                   const DetectorOptions& o) {
    if (widthPerDisparity.size() < kMinWidthSamples || frame.disparity.empty() ||
        frame.disparity.type() != CV_16SC1 || frame.disparity.size() != frame.mask.size())
      return {};
    std::vector<float> ks = widthPerDisparity;
    std::nth_element(ks.begin(), ks.begin() + static_cast<std::ptrdiff_t>(ks.size() / 2), ks.end());
    const double k = ks[ks.size() / 2];
    // The zone's disparities, sampled every 4th pixel.
    depths.clear();
    for (int y = roi.y; y < roi.y + roi.height; y += 4) {
      const auto* row = frame.disparity.ptr<std::int16_t>(y);
      const auto* in = frame.mask.ptr<std::uint8_t>(y);
      for (int x = roi.x; x < roi.x + roi.width; x += 4)
        if (row[x] > 0 && in[x]) depths.push_back(row[x]);
    }
    if (depths.size() < 16) return {};
    auto at = [&](double q) {
      auto it = depths.begin() + static_cast<std::ptrdiff_t>(q * (depths.size() - 1));
      std::nth_element(depths.begin(), it, depths.end());
      return *it / 16.0;
    };
    const double far = at(o.depthFacePercentiles[0]), near = at(o.depthFacePercentiles[1]);
    return {static_cast<int>(std::floor(k * far / o.depthFaceMargin)),
            static_cast<int>(std::ceil(k * near * o.depthFaceMargin))};
  }
};

namespace {

cv::Mat ellipse(int diameter) {
  return cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(diameter, diameter));
}

// The fraction of mask pixels in the central half of a face box.
double zoneCover(const cv::Mat& mask, const cv::Rect& box) {
  if (mask.empty()) return 0;
  const cv::Rect centre =
      cv::Rect(box.x + box.width / 4, box.y + box.height / 4, box.width / 2, box.height / 2) &
      cv::Rect(0, 0, mask.cols, mask.rows);
  if (centre.empty()) return 0;
  return cv::countNonZero(mask(centre)) / static_cast<double>(centre.area());
}

}  // namespace

Detector::Detector(DetectorOptions options)
    : options_(std::move(options)), impl_(std::make_unique<Impl>()) {
  const DetectorOptions& o = options_;
  if (!(o.scaleFactor > 1.0 && o.scaleFactor < 2.0))
    throw Error("face scale factor must be in (1, 2), e.g. 1.1");
  if (o.minNeighbors < 0) throw Error("face minNeighbors must be >= 0");
  if (o.fullSearchEvery < 1 || !(o.followMarginFaces >= 0 && o.followMarginFaces <= 10) ||
      o.followMissFrames < 0 || o.exhaustiveSearchEvery < 0 || !(o.skinGuideArea >= 0))
    throw Error(
        "fullSearchEvery must be >= 1, followMarginFaces within 0..10, followMissFrames, "
        "exhaustiveSearchEvery and skinGuideArea >= 0");
  if (!(o.faceScale >= 0.25 && o.faceScale <= 1)) throw Error("face scale must be in [0.25, 1]");
  if (!(o.depthFacePercentiles[0] >= 0 && o.depthFacePercentiles[0] <= o.depthFacePercentiles[1] &&
        o.depthFacePercentiles[1] <= 1) ||
      !(o.depthFaceMargin >= 1))
    throw Error("depth face sizes need percentiles 0 <= far <= near <= 1 and a margin >= 1");
  if (o.minFacePx != 0 && o.minFacePx < 20)
    throw Error(
        "the smallest face must be >= 20 px (the cascade's window), or 0 for a 16th of the width");
  if (o.maskErodePx < -1 || o.maskClosePx < 0 || o.openPx < 0 || o.closePx < 0 ||
      o.minHandAreaPx < 1)
    throw Error("mask growth, opening and closing must be >= 0 px and the hand area >= 1 px");
  if (!std::filesystem::exists(o.faceCascade))
    throw Error(
        "face cascade '" + o.faceCascade +
        "' not found: install Debian's opencv-data (scripts/setup.sh) or pass another file");
  if (!impl_->cascade.load(o.faceCascade))
    throw Error("cannot load the face cascade '" + o.faceCascade + "'");
  if (o.openPx > 0) impl_->openKernel = ellipse(o.openPx);
  if (o.closePx > 0) impl_->closeKernel = ellipse(o.closePx);
  if (o.maskClosePx > 0) impl_->maskCloseKernel = ellipse(o.maskClosePx);
}

Detector::~Detector() = default;
Detector::Detector(Detector&&) noexcept = default;

Detections Detector::detect(const Frame& frame) {
  const DetectorOptions& o = options_;
  Impl& m = *impl_;
  if (frame.left.empty() || (frame.left.type() != CV_8UC3 && frame.left.type() != CV_8UC1))
    throw Error("detection needs the left image in colour (BGR) or grey (faces only)");
  cv::Mat colour = frame.left;
  if (colour.channels() == 1) cv::cvtColor(frame.left, colour, cv::COLOR_GRAY2BGR);  // no skin
  const cv::Rect image(0, 0, frame.left.cols, frame.left.rows);
  const bool region = o.scope == DetectionScope::HoropterRegion;
  if (!frame.mask.empty() && frame.mask.size() != frame.left.size())
    throw Error("the zone mask and the left image differ in size");
  if (region && frame.mask.empty())
    throw Error("detection in the horopter region needs Frame::mask: run the mask stage first");

  Detections d;
  d.scope = o.scope;
  // Where to look, and the eroded mask over it.
  cv::Rect roi = image;
  if (region) {
    roi = cv::boundingRect(frame.mask);
    if (roi.empty()) return d;
    const int g = o.maskClosePx;
    roi = cv::Rect(roi.x - g, roi.y - g, roi.width + 2 * g, roi.height + 2 * g) & image;
    m.grown = frame.mask(roi).clone();
    if (!m.maskCloseKernel.empty())
      cv::morphologyEx(m.grown, m.grown, cv::MORPH_CLOSE, m.maskCloseKernel);
    const int erodePx = o.maskErodePx >= 0 ? o.maskErodePx : std::max(1, frame.left.cols / 160);
    if (erodePx > 0) {
      if (m.erodeKernel.rows != 2 * erodePx + 1) m.erodeKernel = ellipse(2 * erodePx + 1);
      cv::erode(m.grown, m.grown, m.erodeKernel);
    }
  }
  d.searched = roi;
  d.searchedPixels = roi.area();

  // Faces: the cascade is unsteady on a face at the border of its image, so
  // the region's rectangle gets half the smallest face of margin.
  int minFace = o.minFacePx > 0 ? o.minFacePx : std::max(20, frame.left.cols / 16);
  int maxFaceAny = 0;  // 0: no limit
  double scale = std::min(1.0, std::max(o.faceScale, 20.0 / minFace));
  // In the region, the zone's depths bound the faces' sizes (width = k d,
  // k learnt from the faces found so far): fewer pyramid levels. (Scaling
  // the image down to the smallest size allowed was faster still, but the
  // cascade then missed faces: on tuning seed 5009 it lost the face for
  // good.)
  const FaceSizeRange depthSizes =
      region && o.depthFaceSizes ? m.faceSizesFromDepth(frame, roi, o) : FaceSizeRange{};
  if (depthSizes.valid()) {
    minFace = std::max(minFace, depthSizes.minPx);
    maxFaceAny = std::max(minFace, depthSizes.maxPx);
  }
  d.faceSizes = cv::Size(minFace, maxFaceAny);
  const int pad = region ? minFace / 2 : 0;
  const cv::Rect faceRoi =
      cv::Rect(roi.x - pad, roi.y - pad, roi.width + 2 * pad, roi.height + 2 * pad) & image;
  const int minSize = std::max(20, cvRound(minFace * scale));
  std::vector<cv::Rect> boxes;  // image coordinates
  // The cascade over `area` (image coordinates) for faces up to maxFace px wide (0: any).
  auto search = [&](const cv::Rect& area, int maxFace) {
    if (area.width < minFace || area.height < minFace) return;
    cv::cvtColor(colour(area), m.grey, cv::COLOR_BGR2GRAY);
    if (scale != 1) cv::resize(m.grey, m.grey, cv::Size(), scale, scale, cv::INTER_AREA);
    std::vector<cv::Rect> found;
    if (maxFaceAny > 0) maxFace = maxFace > 0 ? std::min(maxFace, maxFaceAny) : maxFaceAny;
    const int maxSize = maxFace > 0 ? std::max(minSize, cvRound(maxFace * scale)) : 0;
    m.cascade.detectMultiScale(m.grey, found, o.scaleFactor, o.minNeighbors, 0,
                               cv::Size(minSize, minSize), cv::Size(maxSize, maxSize));
    const double k = 1 / scale;
    for (const cv::Rect& b : found)
      boxes.emplace_back(cvRound(b.x * k) + area.x, cvRound(b.y * k) + area.y, cvRound(b.width * k),
                         cvRound(b.height * k));
  };
  // Skin in the zone: where the hands are looked for below, and what guides
  // the full face searches.
  o.skin.classify(colour, roi, m.skin);
  if (region) cv::bitwise_and(m.skin, m.grown, m.skin);
  // The windows a guided full search looks in: around each skin blob large
  // enough to hold a face (a face is skin; in the region, in the zone).
  auto skinWindows = [&] {
    std::vector<cv::Rect> windows;
    const int n =
        cv::connectedComponentsWithStats(m.skin, m.labels, m.stats, m.centroids, 8, CV_32S);
    for (int i = 1; i < n; ++i) {
      const cv::Rect b(
          m.stats.at<int>(i, cv::CC_STAT_LEFT) + roi.x, m.stats.at<int>(i, cv::CC_STAT_TOP) + roi.y,
          m.stats.at<int>(i, cv::CC_STAT_WIDTH), m.stats.at<int>(i, cv::CC_STAT_HEIGHT));
      if (m.stats.at<int>(i, cv::CC_STAT_AREA) < o.skinGuideArea * minFace * minFace ||
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
  auto kept = [&](const cv::Rect& b) { return !region || zoneCover(frame.mask, b) >= 0.3; };
  const bool follow = !m.followed.empty() && m.sinceFullSearch + 1 < o.fullSearchEvery;
  bool searchAll = !follow;
  if (follow) {
    ++m.sinceFullSearch;
    for (const Impl::Followed& followed : m.followed) {
      const cv::Rect& f = followed.box;
      const int g = cvRound(o.followMarginFaces * f.width);
      search(cv::Rect(f.x - g, f.y - g, f.width + 2 * g, f.height + 2 * g) & faceRoi, 2 * f.width);
    }
    dedupe();
    // followMissFrames 0: a followed face not found again makes this frame
    // search everywhere after all.
    if (o.followMissFrames == 0 && static_cast<std::size_t>(std::count_if(
                                       boxes.begin(), boxes.end(), kept)) < m.followed.size()) {
      boxes.clear();
      searchAll = true;
    }
  }
  if (searchAll) {
    m.sinceFullSearch = 0;
    // While a face is followed, guided by skin, but every
    // exhaustiveSearchEvery-th full search looks everywhere (a face the skin
    // model misses); with no face yet, everywhere (a face found a frame
    // late is elected a frame late).
    const bool guided =
        region && o.exhaustiveSearchEvery != 1 && !m.followed.empty() &&
        (o.exhaustiveSearchEvery == 0 || ++m.sinceExhaustive < o.exhaustiveSearchEvery);
    if (guided) {
      for (const cv::Rect& w : skinWindows())
        search(w, 0);
      dedupe();
    } else {
      m.sinceExhaustive = 0;
      search(faceRoi, 0);
    }
  }
  d.fullFaceSearch = searchAll;
  for (const cv::Rect& b : boxes) {
    FaceDetection f;
    f.box = b;
    f.centre = cv::Point2f(b.x + 0.5f * b.width, b.y + 0.5f * b.height);
    f.width = static_cast<float>(b.width);
    f.insideZone = zoneCover(frame.mask, b) >= 0.3;
    if (!kept(b)) continue;  // the region holds the zone only
    d.faces.push_back(f);
  }
  if (region && o.depthFaceSizes) m.learnFaceWidthPerDisparity(frame, d.faces);
  // Followed next frame: the faces found, and those not found again for at
  // most followMissFrames frames (the cascade misses a face now and then; a
  // miss then costs no full search).
  std::vector<Impl::Followed> next;
  for (const FaceDetection& f : d.faces)
    next.push_back({f.box, 0});
  for (const Impl::Followed& f : m.followed) {
    const cv::Point2f c(f.box.x + 0.5f * f.box.width, f.box.y + 0.5f * f.box.height);
    const bool foundAgain =
        std::any_of(d.faces.begin(), d.faces.end(), [&](const FaceDetection& g) {
          return cv::norm(g.centre - c) < std::max(g.width, static_cast<float>(f.box.width));
        });
    if (!foundAgain && f.missed < o.followMissFrames) next.push_back({f.box, f.missed + 1});
  }
  m.followed = std::move(next);
  std::sort(d.faces.begin(), d.faces.end(), [](const FaceDetection& a, const FaceDetection& b) {
    return std::tie(a.box.x, a.box.y, a.box.width) < std::tie(b.box.x, b.box.y, b.box.width);
  });

  // Hands: skin (classified above) that is neither a face nor a neck.
  const bool haveDisparity = region && !frame.disparity.empty() &&
                             frame.disparity.type() == CV_16SC1 &&
                             frame.disparity.size() == frame.left.size();
  for (const FaceDetection& f : d.faces) {
    const int mx = static_cast<int>(o.faceMargin * f.box.width);
    cv::Rect out(f.box.x - mx - roi.x, f.box.y - mx - roi.y, f.box.width + 2 * mx,
                 f.box.height + mx + static_cast<int>(o.neckFraction * f.box.height) + mx);
    out &= cv::Rect(0, 0, roi.width, roi.height);
    if (!out.empty()) m.skin(out).setTo(0);
  }
  if (!m.openKernel.empty()) cv::morphologyEx(m.skin, m.skin, cv::MORPH_OPEN, m.openKernel);
  if (!m.closeKernel.empty()) cv::morphologyEx(m.skin, m.skin, cv::MORPH_CLOSE, m.closeKernel);
  const int n = cv::connectedComponentsWithStats(m.skin, m.labels, m.stats, m.centroids, 8, CV_32S);
  cv::distanceTransform(m.skin, m.distance, cv::DIST_L2, 3);
  std::vector<float> radius(static_cast<std::size_t>(n), 0.f);
  // Region: whether each skin pixel really lies at its disparity (the left
  // and right grey levels agree there). Block matching gives a strip of wall
  // beside the silhouette the person's disparity; at the pixel the wall's
  // texture then disagrees.
  const bool stereo = haveDisparity && frame.leftGrey.size() == frame.left.size() &&
                      frame.rightGrey.size() == frame.left.size() &&
                      frame.leftGrey.type() == CV_8UC1 && frame.rightGrey.type() == CV_8UC1;
  std::vector<int> agree(static_cast<std::size_t>(n), 0), measured(static_cast<std::size_t>(n), 0);
  for (int y = 0; y < m.skin.rows; ++y) {
    const auto* l = m.labels.ptr<int>(y);
    const auto* dist = m.distance.ptr<float>(y);
    const std::int16_t* disp = stereo ? frame.disparity.ptr<std::int16_t>(y + roi.y) : nullptr;
    const std::uint8_t* lg = stereo ? frame.leftGrey.ptr<std::uint8_t>(y + roi.y) : nullptr;
    const std::uint8_t* rg = stereo ? frame.rightGrey.ptr<std::uint8_t>(y + roi.y) : nullptr;
    for (int x = 0; x < m.skin.cols; ++x) {
      if (l[x] <= 0) continue;
      radius[l[x]] = std::max(radius[l[x]], dist[x]);
      if (!stereo || disp[x + roi.x] <= 0) continue;
      const int xr = x + roi.x - (disp[x + roi.x] + 8) / 16;
      if (xr < 0) continue;
      ++measured[l[x]];
      if (std::abs(int(lg[x + roi.x]) - int(rg[xr])) <= o.stereoAgreeGrey) ++agree[l[x]];
    }
  }
  for (int i = 1; i < n; ++i) {
    const int area = m.stats.at<int>(i, cv::CC_STAT_AREA);
    if (area < o.minHandAreaPx) continue;
    HandDetection h;
    h.areaPx = area;
    h.radiusPx = radius[static_cast<std::size_t>(i)];
    if (measured[static_cast<std::size_t>(i)] > 0)
      h.stereoAgreement = static_cast<float>(agree[static_cast<std::size_t>(i)]) /
                          measured[static_cast<std::size_t>(i)];
    h.box = cv::Rect(m.stats.at<int>(i, cv::CC_STAT_LEFT) + roi.x,
                     m.stats.at<int>(i, cv::CC_STAT_TOP) + roi.y,
                     m.stats.at<int>(i, cv::CC_STAT_WIDTH), m.stats.at<int>(i, cv::CC_STAT_HEIGHT));
    h.centroid = cv::Point2f(static_cast<float>(m.centroids.at<double>(i, 0) + roi.x),
                             static_cast<float>(m.centroids.at<double>(i, 1) + roi.y));
    const cv::Point c(cvRound(h.centroid.x), cvRound(h.centroid.y));
    if (region) {
      const cv::Point local = c - roi.tl();
      h.insideZone = local.x >= 0 && local.y >= 0 && local.x < m.grown.cols &&
                     local.y < m.grown.rows && m.grown.at<std::uint8_t>(local) != 0;
    } else {
      h.insideZone =
          !frame.mask.empty() && image.contains(c) && frame.mask.at<std::uint8_t>(c) != 0;
    }
    d.hands.push_back(h);
  }
  std::sort(d.hands.begin(), d.hands.end(), [](const HandDetection& a, const HandDetection& b) {
    return std::tie(b.areaPx, a.centroid.x, a.centroid.y) <
           std::tie(a.areaPx, b.centroid.x, b.centroid.y);
  });

  // The triangle of the largest in-zone face (any face over the full image).
  const FaceDetection* best = nullptr;
  for (const FaceDetection& f : d.faces)
    if ((f.insideZone || !region) && (!best || f.width > best->width)) best = &f;
  if (best) {
    const HandDetection *left = nullptr, *right = nullptr;
    auto dist = [&](const HandDetection& h) { return cv::norm(h.centroid - best->centre); };
    for (const HandDetection& h : d.hands) {
      const HandDetection*& side = h.centroid.x >= best->centre.x ? left : right;
      if (!side || dist(h) < dist(*side)) side = &h;
    }
    if (left && right) d.triangle = bodyTriangle(best->centre, left->centroid, right->centroid);
  }
  return d;
}

namespace {

class DetectionStage : public Stage {
 public:
  explicit DetectionStage(DetectorOptions options) : detector_(std::move(options)) {}
  std::string name() const override { return "detection"; }
  void process(Frame& frame) override {
    frame.detections = std::make_shared<const Detections>(detector_.detect(frame));
  }

 private:
  Detector detector_;
};

}  // namespace

std::unique_ptr<Stage> makeDetectionStage(DetectorOptions options) {
  return std::make_unique<DetectionStage>(std::move(options));
}

}  // namespace horopter
