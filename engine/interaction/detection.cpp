// Face and hand detection inside the zone or over the whole image; see
// horopter/interaction/detection.hpp.
#include "horopter/interaction/detection.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cstdlib>

#include "body_face.hpp"
#include "face_search.hpp"
#include "horopter/core/error.hpp"
#include "shirt_skin.hpp"

namespace horopter {

const char* detectionScopeName(DetectionScope scope) {
  return scope == DetectionScope::HoropterRegion ? "horopter-region" : "full-image";
}

namespace {
constexpr int kNoHead = 1 << 20;  // frames since the last head, when there was none
}  // namespace

struct Detector::Impl {
  explicit Impl(const DetectorOptions& options) : faces(options), acquiring(options) {
    acquiring.faceScale = options.acquisitionFaceScale;
  }
  detail::FaceSearch faces;
  DetectorOptions acquiring;  // the options with the acquisition's face scale
  bool facesFound = false;    // in the previous frame
  cv::Mat skin, grown, grey, bright, labels, stats, centroids, distance;
  float faceLuma = 0;       // the skin's grey level in the last head found (0: none yet)
  int sinceHead = kNoHead;  // frames since that head
  float clothLuma = 0;      // skin darker than this is a skin-coloured shirt (0: none seen)
  std::vector<std::int16_t> depths;  // scratch
  cv::Mat openKernel, closeKernel, maskCloseKernel, erodeKernel;
};

namespace {

cv::Mat ellipse(int diameter) {
  return cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(diameter, diameter));
}

}  // namespace

std::span<const NumberOption<DetectorOptions>> detectorOptions() {
  using O = DetectorOptions;
  static const NumberOption<O> table[] = {
      {"fullSearchEvery", "--full-search-every", "frames", 1, 1000,
       "search the whole region (or image) for faces every Nth frame; between, follow the "
       "previous frame's faces",
       &O::fullSearchEvery},
      {"followMissFrames", "--follow-miss-frames", "frames", 0, 1000,
       "a followed face not found again is looked for around its last place this many frames "
       "before a full search",
       &O::followMissFrames},
      {"followSizeRatio", "--follow-size-ratio", "", 0, 4,
       "following, the cascade looks for faces from 1/X to X times the followed face's width, "
       "around where its last step takes it (0: from the smallest face to twice its width, one "
       "face width around it)",
       &O::followSizeRatio},
      {"followSlackFaces", "--follow-slack-faces", "face widths", 0, 10,
       "with --follow-size-ratio, the window's margin beyond the face's last step",
       &O::followSlackFaces},
      {"followFacePx", "--follow-face-px", "px", 0, 200,
       "with --follow-size-ratio, the image is scaled (at most by --face-scale) so that the "
       "followed face is this wide (0: --face-scale)",
       &O::followFacePx},
      {"exhaustiveSearchEvery", "--exhaustive-search-every", "searches", 0, 1000,
       "region, a face followed: full searches look only around skin blobs but one in N "
       "(0: never everywhere)",
       &O::exhaustiveSearchEvery},
      {"faceScale", "--face-scale", "", 0.25, 1,
       "the face cascade runs on the image scaled by this once a face is followed", &O::faceScale},
      {"acquisitionFaceScale", "--acquisition-face-scale", "", 0.25, 1,
       "... and by this while no face was found in the previous frame", &O::acquisitionFaceScale},
      {"minNeighbors", "--min-neighbors", "", 0, 100, "the face cascade's grouping threshold",
       &O::minNeighbors},
      {"faceZoneCover", "--face-zone-cover", "", 0, 1,
       "a face is inside the zone when the mask covers this fraction of its central half",
       &O::faceZoneCover},
      {"minSkinLumaOfFace", "--min-skin-luma", "", 0, 4,
       "hand skin darker than this fraction of the face's skin is not skin (0: off)",
       &O::minSkinLumaOfFace},
      {"bodyFaceBelowFaces", "--body-face-below", "face widths", 0, 10,
       "a face whose centre lies this far below the followed head's, at its depth, is on its "
       "body: no face (0: off)",
       &O::bodyFaceBelowFaces},
      {"bodyFaceSideFaces", "--body-face-side", "face widths", 0, 10,
       "... within this distance of the head's vertical", &O::bodyFaceSideFaces},
      {"bodyFaceDepthFraction", "--body-face-depth", "", 0, 1,
       "... at a disparity within this fraction of the head's", &O::bodyFaceDepthFraction},
      {"bodyFaceDarkFraction", "--body-face-dark", "", 0, 1,
       "a face whose skin is darker than this fraction of the followed head's is on its body: "
       "no face (0: off)",
       &O::bodyFaceDarkFraction},
      {"bodyFaceMemoryFrames", "--body-face-memory", "frames", 0, 1000,
       "... of the last head found within this many frames, too", &O::bodyFaceMemoryFrames},
      {"shirtLumaOfTorso", "--shirt-luma", "", 0, 4,
       "where the shirt under the followed head is skin-coloured, skin darker than this "
       "multiple of the chest's is cloth (0: off)",
       &O::shirtLumaOfTorso},
      {"shirtSkinFraction", "--shirt-skin-fraction", "", 0, 1,
       "... the shirt is skin-coloured when this fraction of the chest's sample is skin",
       &O::shirtSkinFraction},
      {"shirtDarkerThanFace", "--shirt-face-luma", "", 0, 1,
       "... and its skin is darker than this fraction of the face's", &O::shirtDarkerThanFace},
      {"shirtSampleTopFaces", "--shirt-sample-top", "face widths", 0, 10,
       "the chest's sample: from this far under the head's centre ...", &O::shirtSampleTopFaces},
      {"shirtSampleBottomFaces", "--shirt-sample-bottom", "face widths", 0, 10,
       "... to this far under it ...", &O::shirtSampleBottomFaces},
      {"shirtSampleHalfWidthFaces", "--shirt-sample-half-width", "face widths", 0, 5,
       "... and this far either side of its vertical", &O::shirtSampleHalfWidthFaces},
  };
  return table;
}

Detector::Detector(DetectorOptions options) : options_(std::move(options)) {
  const DetectorOptions& o = options_;
  checkRanges(detectorOptions(), o);
  if (o.maskErodePx < -1 || o.maskClosePx < 0 || o.openPx < 0 || o.closePx < 0 ||
      o.minHandAreaPx < 1)
    throw Error("mask growth, opening and closing must be >= 0 px and the hand area >= 1 px");
  impl_ = std::make_unique<Impl>(o);  // checks the face options, loads the cascade
  if (o.openPx > 0) impl_->openKernel = ellipse(o.openPx);
  if (o.closePx > 0) impl_->closeKernel = ellipse(o.closePx);
  if (o.maskClosePx > 0) impl_->maskCloseKernel = ellipse(o.maskClosePx);
}

Detector::~Detector() = default;
Detector::Detector(Detector&&) noexcept = default;

Detections Detector::detect(const StereoFrame& frame) {
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

  // Skin in the zone: where the hands are looked for below, and what guides
  // the full face searches.
  o.skin.classify(colour, roi, m.skin);
  if (region) cv::bitwise_and(m.skin, m.grown, m.skin);
  detail::FaceSearchResult faces =
      m.faces.find(m.facesFound ? o : m.acquiring, frame, colour, roi, m.skin);
  m.facesFound = !faces.faces.empty();
  d.faces = std::move(faces.faces);
  d.faceSizes = faces.faceSizes;
  d.fullFaceSearch = faces.fullSearch;

  // Hands: skin (classified above) that is neither a face nor a neck.
  const bool haveDisparity = region && !frame.disparity.empty() &&
                             frame.disparity.type() == CV_16SC1 &&
                             frame.disparity.size() == frame.left.size();
  // The grey levels over the region: the rectify stage's grey view where
  // there is one (the same conversion, done once per frame).
  if (frame.leftGrey.size() == frame.left.size() && frame.leftGrey.type() == CV_8UC1)
    m.grey = frame.leftGrey(roi);
  else {
    m.grey.release();  // it may still view an earlier frame's grey image: not into that
    cv::cvtColor(colour(roi), m.grey, cv::COLOR_BGR2GRAY);
  }
  for (FaceDetection& f : d.faces) {
    const cv::Rect centre =
        cv::Rect(f.box.x + f.box.width / 4 - roi.x, f.box.y + f.box.height / 4 - roi.y,
                 f.box.width / 2, f.box.height / 2) &
        cv::Rect(0, 0, roi.width, roi.height);
    if (!centre.empty() && cv::countNonZero(m.skin(centre)) > 0)
      f.skinLuma = static_cast<float>(cv::mean(m.grey(centre), m.skin(centre))[0]);
    if (haveDisparity && !centre.empty())
      f.disparityPx = static_cast<float>(
          detail::medianDisparity(frame.disparity, cv::Mat(), centre + roi.tl(), 2, m.depths));
  }
  // The head the detector follows gives the skin's reference luma; a face
  // on its body (or much darker than the last head's, in a frame that
  // missed the head) is no face (body_face.hpp).
  const float remembered = m.sinceHead <= o.bodyFaceMemoryFrames ? m.faceLuma : 0;
  const FaceDetection* head = detail::followedHead(d.faces, region, remembered, o);
  const float headLuma = head ? head->skinLuma : 0;
  // The chest under the head, sampled before any cut, tells a shirt of
  // skin's colour (shirt_skin.hpp).
  const bool haveHead = head != nullptr;
  const detail::TorsoSample chest =
      haveHead ? detail::sampleTorso(m.skin, m.grey, roi, *head, o) : detail::TorsoSample{};
  std::vector<FaceDetection> kept;
  for (const FaceDetection& f : d.faces)
    ((head && detail::faceOnTheBody(f, *head, o)) || detail::muchDarkerThanHead(f, remembered, o)
         ? d.bodyFaces
         : kept)
        .push_back(f);
  d.faces = std::move(kept);  // `head` dangles from here
  if (headLuma > 0) m.faceLuma = headLuma;
  m.sinceHead = headLuma > 0 ? 0 : std::min(m.sinceHead + 1, kNoHead);
  // Without a head, the last one's shirt holds for as long as its luma does.
  if (haveHead)
    m.clothLuma = detail::clothLumaBelow(chest, m.faceLuma, o);
  else if (m.sinceHead > o.bodyFaceMemoryFrames)
    m.clothLuma = 0;
  // Skin darker than a fraction of the face's, or than a skin-coloured
  // shirt's chest allows: cloth whose chroma is skin's, which joins a hand
  // to its sleeve into one blob off the hand. Two compares, not one at the
  // larger cut: merged, tuning seed 10486 gave 646 false detections instead
  // of 648, not yet understood (cv::compare's rounding of a float scalar
  // is the suspect).
  if (o.minSkinLumaOfFace > 0 && m.faceLuma > 0) {
    cv::compare(m.grey, o.minSkinLumaOfFace * m.faceLuma, m.bright, cv::CMP_GE);
    cv::bitwise_and(m.skin, m.bright, m.skin);
  }
  if (m.clothLuma > 0) {
    cv::compare(m.grey, m.clothLuma, m.bright, cv::CMP_GE);
    cv::bitwise_and(m.skin, m.bright, m.skin);
  }
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
  std::vector<std::int64_t> lumaSum(static_cast<std::size_t>(n), 0);
  std::vector<std::int64_t> disparitySum(static_cast<std::size_t>(n), 0);
  for (int y = 0; y < m.skin.rows; ++y) {
    const auto* l = m.labels.ptr<int>(y);
    const auto* dist = m.distance.ptr<float>(y);
    const auto* grey = m.grey.ptr<std::uint8_t>(y);
    const std::int16_t* disp = stereo ? frame.disparity.ptr<std::int16_t>(y + roi.y) : nullptr;
    const std::uint8_t* lg = stereo ? frame.leftGrey.ptr<std::uint8_t>(y + roi.y) : nullptr;
    const std::uint8_t* rg = stereo ? frame.rightGrey.ptr<std::uint8_t>(y + roi.y) : nullptr;
    for (int x = 0; x < m.skin.cols; ++x) {
      if (l[x] <= 0) continue;
      radius[l[x]] = std::max(radius[l[x]], dist[x]);
      lumaSum[l[x]] += grey[x];
      if (!stereo || disp[x + roi.x] <= 0) continue;
      disparitySum[l[x]] += disp[x + roi.x];
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
    h.meanLuma =
        static_cast<float>(lumaSum[static_cast<std::size_t>(i)]) / static_cast<float>(area);
    if (measured[static_cast<std::size_t>(i)] > 0) {
      h.stereoAgreement = static_cast<float>(agree[static_cast<std::size_t>(i)]) /
                          measured[static_cast<std::size_t>(i)];
      h.disparityPx = static_cast<float>(disparitySum[static_cast<std::size_t>(i)]) /
                      (16.0f * static_cast<float>(measured[static_cast<std::size_t>(i)]));
    }
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

}  // namespace horopter
