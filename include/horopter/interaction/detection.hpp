// The detection stage: faces (OpenCV's Haar cascade) and hands (a skin colour
// model, morphology, connected components) in the left rectified image,
// either inside the zone of interaction (Frame::mask) or over the whole image
// (for A/B comparison), and the body triangle head / left hand / right hand.
#pragma once

#include "horopter/core/export.hpp"

#include <span>

#include "horopter/core/option_table.hpp"

#include <opencv2/core.hpp>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "horopter/interaction/skin_model.hpp"
#include "horopter/vision/stereo_frame.hpp"

namespace horopter {

// Debian's opencv-data.
inline constexpr const char* kDefaultFaceCascade =
    "/usr/share/opencv4/haarcascades/haarcascade_frontalface_default.xml";

enum class DetectionScope {
  HoropterRegion,  // only pixels inside the zone (the mask, closed and dilated a little)
  FullImage,       // every pixel: what a detector without the horopter sees
};
HOROPTER_API const char* detectionScopeName(DetectionScope scope);

struct HOROPTER_API DetectorOptions {
  DetectionScope scope = DetectionScope::HoropterRegion;
  std::string faceCascade = kDefaultFaceCascade;
  double scaleFactor = 1.1;  // Haar pyramid step, > 1
  int minNeighbors = 3;      // Haar grouping, >= 0
  // The smallest face searched, full-resolution pixels; 0: a 16th of the
  // image's width (40 px at 640: a face at 2.3 m with a 60 degree view).
  int minFacePx = 0;
  // The cascade runs on the image scaled by this (0.25..1), raised where the
  // smallest face would fall under 20 px: a 40 px face is 30 px at 0.75,
  // for far fewer windows.
  double faceScale = 0.75;
  // ... and at this scale while acquiring (no face found in the previous
  // frame): the face of a person walking into the zone (about 2 m, 45 px) is
  // found frames earlier at full resolution, and every frame before it is
  // a frame of election lost (tuning seeds 5000-5019: region loss 10.0 ->
  // 7.5 % with 1 at all times). Once a face is followed, faceScale.
  double acquisitionFaceScale = 1.0;
  // Following: between full searches of the region (one every
  // fullSearchEvery frames), the cascade looks only around the faces of the
  // previous frame (the window and sizes below); a face not found again there
  // brings a full search in the same frame, so following never loses a face
  // a full search would have found. 1: a full search every frame. (Before
  // that fallback, following every 5th frame raised the region's loss on 20
  // held-out trials from 30.7 to 36.0 %; with it, on the 20 tuning trials
  // of eval-tracking --seed 5000 --frames 200 --scope region, 5 against 1
  // gave 12.01 against 11.77 % loss for 27.9 against 47.1 ms of detection.)
  int fullSearchEvery = 5;
  double followMarginFaces = 1.0;
  // Following, sized and placed by the face itself (followSizeRatio > 0):
  // the cascade looks for widths from w / followSizeRatio to w *
  // followSizeRatio (w: the followed face's), in a window around where its
  // last step takes it, grown by followSlackFaces face widths plus that
  // step's length (at most followMarginFaces face widths), on the image
  // scaled (at most by faceScale) so that the face is followFacePx wide
  // (0: faceScale; on pyramid levels whose window is over 48 px the cascade
  // steps by 1 px instead of 2, four times the windows). followSizeRatio 0:
  // followMarginFaces around its last place, widths from the smallest face
  // to 2 w. The three together, on tuning seeds 10512-10531: the pipeline
  // 187.1 -> 170.4 M instructions per frame (the face search about 53 ->
  // 36 M), region loss 5.84 -> 5.31 % (head 0.43 % both). At 36 px the cascade misses a face in its
  // window now and then (a miss costs a full search in the same frame, not the face).
  double followSizeRatio = 1.25;
  double followSlackFaces = 0.3;
  double followFacePx = 36;
  // A followed face that is not found again is still looked for around its
  // last place for this many frames, without a full search (0: a miss makes
  // the same frame search everywhere).
  int followMissFrames = 0;
  // Region, while a face is followed: a full search looks only around the
  // zone's skin blobs of at least skinGuideArea squared smallest faces (a
  // face is skin), except one in exhaustiveSearchEvery that looks everywhere
  // (1: always everywhere; 0: never). With no face followed, everywhere.
  int exhaustiveSearchEvery = 5;
  double skinGuideArea = 0.2;
  // Region: faces sized by depth. A face's width in pixels is k times its
  // disparity (k = its width in metres over the baseline), learnt from the
  // faces found so far (the median of the last 15; 3 needed); the cascade
  // then looks only for widths from k d_far / margin to k d_near * margin,
  // d_far and d_near the zone's disparity percentiles below.
  bool depthFaceSizes = true;
  double depthFacePercentiles[2] = {0.1, 0.9};
  double depthFaceMargin = 1.4;
  // After this many consecutive full searches sized by depth without a face
  // (about 0.3 s at 30 frames/s), k is forgotten and every size searched
  // until it is learnt again: a k learnt from a false detection would keep
  // the real face out of the sizes searched for good (tuning seeds 10033
  // and 10048: a false face in the zone before the person came, never
  // elected).
  int depthSizeForgetSearches = 10;
  // A face is inside the zone when the mask covers at least this fraction of
  // its central half (the region keeps only those), in [0, 1].
  double faceZoneCover = 0.3;
  // Region: the mask is closed with a disc this wide (0: not), then eroded
  // by maskErodePx: block matching fattens the foreground by about half its
  // block, so a rim of the background behind the silhouette (skin-coloured
  // wood, say) gets the person's disparity; the erosion takes it out.
  int maskClosePx = 11;
  int maskErodePx = -1;  // -1: a 160th of the width (4 px at 640, StereoBM's block 9)
  SkinModel skin;
  // Once a face's skin luma is known (FaceDetection::skinLuma), hand skin
  // darker than this fraction of it is not skin (0: off): cloth whose chroma
  // is skin's is far darker than skin under the same light, and would join
  // a hand to its sleeve into one blob whose centroid is off the hand
  // (tuning seed 10053, a brown shirt).
  double minSkinLumaOfFace = 0.5;
  // Faces on the body (tuning seed 10486: the cascade found a "face" on a
  // shirt of skin's chroma, 2.5 face widths under the head at the torso's
  // depth, with half the face's grey level). The face the detector follows
  // (the largest in the zone that is on no other's body) gives the skin's
  // reference luma above; a face on its body is no face: it goes to
  // Detections::bodyFaces, with no face-and-neck cut, no reference luma and
  // no election. On the body: its centre at least bodyFaceBelowFaces head
  // widths below the head's (0: this half off), within bodyFaceSideFaces
  // of its vertical, at a disparity within bodyFaceDepthFraction of the
  // head's; or its skin darker than bodyFaceDarkFraction of the head's (0:
  // this half off), which holds against the last head found within
  // bodyFaceMemoryFrames frames too (a frame that missed the real face).
  double bodyFaceBelowFaces = 1.0;
  double bodyFaceSideFaces = 1.5;
  double bodyFaceDepthFraction = 0.15;
  double bodyFaceDarkFraction = 0.7;
  int bodyFaceMemoryFrames = 15;
  // A shirt of skin's colour (tuning seeds 10146, 10486): its sleeves, lit
  // from their side, pass the face-relative cut above and join a hand at
  // rest into one blob up the arm. Under the followed head (or the last one,
  // within bodyFaceMemoryFrames), the chest is sampled from
  // shirtSampleTopFaces to shirtSampleBottomFaces head widths below its
  // centre and shirtSampleHalfWidthFaces either side; where at least
  // shirtSkinFraction of the sample is skin, with a median grey level under
  // shirtDarkerThanFace of the face's, skin darker than shirtLumaOfTorso
  // times that level is cloth (0: off).
  double shirtLumaOfTorso = 1.3;
  double shirtSkinFraction = 0.5;
  double shirtDarkerThanFace = 0.8;
  double shirtSampleTopFaces = 1.5;
  double shirtSampleBottomFaces = 2.7;
  double shirtSampleHalfWidthFaces = 0.5;
  int openPx = 5;          // morphological opening of the skin mask (removes speckle, thin strips)
  int closePx = 7;         // closing (joins a hand's pieces)
  int minHandAreaPx = 40;  // smallest skin component kept as a hand candidate
  int stereoAgreeGrey = 12;  // grey levels within which left and right agree (HandDetection)
  // The face rectangle grown by this fraction of its width, and down by
  // neckFraction of its height, is not a hand (face and neck skin).
  double faceMargin = 0.3;
  double neckFraction = 0.8;
};

struct HOROPTER_API FaceDetection {
  cv::Rect box;
  cv::Point2f centre;
  float width = 0;          // pixels
  bool insideZone = false;  // the mask covers most of the face's central part
  // The mean grey level of the skin in the face's central half (0: none):
  // the subject's skin under this light, which the hands share.
  float skinLuma = 0;
  // Region: the median valid disparity in its central half, px (0: none).
  float disparityPx = 0;
};

struct HOROPTER_API HandDetection {
  cv::Point2f centroid;
  cv::Rect box;
  int areaPx = 0;
  bool insideZone = false;  // the centroid lies in the (eroded) mask
  // The radius of the largest disc inside the component (the distance
  // transform's maximum): a hand is a disc about 0.3 face widths across, while
  // the slivers of skin-coloured wall that block matching's fattened
  // silhouette lets into the zone are a few pixels thick, however long.
  float radiusPx = 0;
  // Region: the fraction of its pixels whose left and right grey levels
  // agree (within DetectorOptions::stereoAgreeGrey) at their disparity; 1
  // where not measured (full image, no disparity).
  float stereoAgreement = 1;
  // The mean grey level of its pixels. Skin-coloured cloth is much darker
  // than skin under the same light (its chroma is skin's only because YCrCb
  // chroma shrinks with luma): TrackerOptions::minHandLumaOfFace.
  float meanLuma = 0;
  // Region: the mean of its valid disparities, px (0: none measured).
  float disparityPx = 0;
};

// The body triangle of one person. Left and right are the person's own.
struct HOROPTER_API BodyTriangle {
  cv::Point2f head, leftHand, rightHand;
  cv::Point2f incentre;     // the centre of the inscribed circle
  double perimeter = 0;     // pixels
  double headAngleRad = 0;  // interior angle at the head vertex
  bool degenerate = false;  // collinear or repeated vertices (incentre = centroid)
};
HOROPTER_API BodyTriangle bodyTriangle(cv::Point2f head, cv::Point2f leftHand,
                                       cv::Point2f rightHand);

struct HOROPTER_API Detections {
  DetectionScope scope = DetectionScope::HoropterRegion;
  std::vector<FaceDetection> faces;  // sorted by position (deterministic)
  // Faces the cascade found on the followed head's body (DetectorOptions::
  // bodyFace*): no faces, kept apart for diagnosis.
  std::vector<FaceDetection> bodyFaces;
  std::vector<HandDetection> hands;  // skin components that are not faces, largest first
  // The largest in-zone face with the nearest hand candidate on each side
  // (the person's left hand appears on the image's right).
  std::optional<BodyTriangle> triangle;
  cv::Rect searched;                // the rectangle the detectors ran over
  cv::Size faceSizes;               // the face widths searched, px (height 0: no upper limit)
  bool fullFaceSearch = true;       // faces searched over the whole region (not only followed)
  std::int64_t searchedPixels = 0;  // pixels the skin model classified
};

// The detector's options a user tunes (flags, help, ranges, JSON keys); validation
// checks them against it.
HOROPTER_API std::span<const NumberOption<DetectorOptions>> detectorOptions();

// Runs both detectors on one frame. Not thread-safe (one per pipeline lane).
class HOROPTER_API Detector {
 public:
  // Throws horopter::Error for bad options or a cascade that cannot be loaded.
  explicit Detector(DetectorOptions options);
  ~Detector();
  Detector(Detector&&) noexcept;
  // frame.left (BGR) and, for the region and the zone flags, frame.mask.
  Detections detect(const StereoFrame& frame);
  const DetectorOptions& options() const { return options_; }

 private:
  struct Impl;
  DetectorOptions options_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace horopter
