// Faces that are not faces: the Haar cascade now and then finds a "face" on
// the body, where a shirt of skin's chroma shows a face-like pattern (tuning
// seed 10486: 76 px wide, 2.5 face widths under the head, at the torso's
// depth, with half the face's grey level). Such a face must not give the
// skin's reference grey level, have its "neck" cut out of the hands or be
// elected. Internal to engine/interaction; the options are DetectorOptions'
// bodyFace*.
#pragma once

#include <span>

#include "horopter/interaction/detection.hpp"

namespace horopter::detail {

// `face` lies below `head` (its centre at least bodyFaceBelowFaces head
// widths lower, within bodyFaceSideFaces head widths of the head's
// vertical) at the head's depth (disparities, both measured, within
// bodyFaceDepthFraction of the head's). Off at bodyFaceBelowFaces 0.
bool belowAtBodyDepth(const FaceDetection& face, const FaceDetection& head,
                      const DetectorOptions& o);

// `face`'s skin is darker than bodyFaceDarkFraction of `headLuma` (both
// measured): cloth of skin's chroma under the light the face is in. Off at
// bodyFaceDarkFraction 0.
bool muchDarkerThanHead(const FaceDetection& face, float headLuma, const DetectorOptions& o);

// Either of the two: `face` is a patch of `head`'s body, not a face.
bool faceOnTheBody(const FaceDetection& face, const FaceDetection& head, const DetectorOptions& o);

// The head the detector follows among `faces`: of those that may be the
// subject's (inside the zone, or any over the full image), not much darker
// than `rememberedLuma` (the last head's skin luma; 0: none) and on the
// body of no other such face, the largest. nullptr when there is none.
const FaceDetection* followedHead(std::span<const FaceDetection> faces, bool region,
                                  float rememberedLuma, const DetectorOptions& o);

}  // namespace horopter::detail
