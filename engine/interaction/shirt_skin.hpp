// A shirt of skin's colour: its cloth passes the skin model and, lit from
// the side a sleeve faces, the face-relative luma cut too (tuning seeds
// 10146 and 10486: sleeves at 0.53-0.68 of the face's grey level), so a hand
// at rest joins its sleeve into one blob whose centroid lies up the arm.
// The torso under the followed head shows the cloth's own grey level; skin
// darker than a multiple of it is cloth, whatever the face's level. Internal
// to engine/interaction; the options are DetectorOptions' shirt*.
#pragma once

#include <opencv2/core.hpp>

#include "horopter/interaction/detection.hpp"

namespace horopter::detail {

// What the chest under a head shows: how much of it is skin, and that
// skin's median grey level.
struct TorsoSample {
  int pixels = 0;          // of the sample box inside the searched region
  float skinFraction = 0;  // of those, classified skin
  float skinLuma = 0;      // the median grey level of those skin pixels (0: none)
};

// The box the chest is sampled in, in image pixels: under the head's centre
// from shirtSampleTopFaces to shirtSampleBottomFaces head widths, and
// shirtSampleHalfWidthFaces head widths either side of its vertical.
cv::Rect torsoBox(const FaceDetection& head, const DetectorOptions& o);

// The sample of `skin` (CV_8UC1, 0 or not) and `grey` (CV_8UC1), both
// covering `roi` of the image, in torsoBox(head, o).
TorsoSample sampleTorso(const cv::Mat& skin, const cv::Mat& grey, const cv::Rect& roi,
                        const FaceDetection& head, const DetectorOptions& o);

// The grey level under which skin is cloth, given the sample and the face's
// skin grey level: shirtLumaOfTorso times the chest's, where at least
// shirtSkinFraction of the chest is skin and its level is below
// shirtDarkerThanFace of the face's (a shirt as bright as skin cannot be
// told from a hand by its level). 0: no such shirt, or the rule is off.
float clothLumaBelow(const TorsoSample& torso, float faceLuma, const DetectorOptions& o);

}  // namespace horopter::detail
