// A hand candidate for the tracker's tests: a disc at `at` of the given
// inscribed radius, inside the zone; areaPx 0: the disc's area.
#pragma once

#include <opencv2/core.hpp>

#include "horopter/interaction/detection.hpp"

namespace horopter::testing {

inline HandDetection handCandidate(cv::Point2f at, float radiusPx = 12, float agreement = 1,
                                   int areaPx = 0) {
  HandDetection h;
  h.centroid = at;
  h.areaPx = areaPx > 0 ? areaPx : static_cast<int>(3.14f * radiusPx * radiusPx);
  h.box = cv::Rect(cvRound(at.x - radiusPx), cvRound(at.y - radiusPx), cvRound(2 * radiusPx),
                   cvRound(2 * radiusPx));
  h.radiusPx = radiusPx;
  h.stereoAgreement = agreement;
  h.insideZone = true;
  return h;
}

}  // namespace horopter::testing
