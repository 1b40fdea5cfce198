// Faces on the body; see body_face.hpp.
#include "body_face.hpp"

#include <cmath>

namespace horopter::detail {

bool belowAtBodyDepth(const FaceDetection& face, const FaceDetection& head,
                      const DetectorOptions& o) {
  if (!(o.bodyFaceBelowFaces > 0) || !(head.width > 0)) return false;
  const double w = head.width;
  const bool below = face.centre.y - head.centre.y >= o.bodyFaceBelowFaces * w &&
                     std::abs(face.centre.x - head.centre.x) <= o.bodyFaceSideFaces * w;
  return below && face.disparityPx > 0 && head.disparityPx > 0 &&
         std::abs(face.disparityPx - head.disparityPx) <=
             o.bodyFaceDepthFraction * head.disparityPx;
}

bool muchDarkerThanHead(const FaceDetection& face, float headLuma, const DetectorOptions& o) {
  return o.bodyFaceDarkFraction > 0 && face.skinLuma > 0 && headLuma > 0 &&
         face.skinLuma < o.bodyFaceDarkFraction * headLuma;
}

bool faceOnTheBody(const FaceDetection& face, const FaceDetection& head, const DetectorOptions& o) {
  return &face != &head &&
         (belowAtBodyDepth(face, head, o) || muchDarkerThanHead(face, head.skinLuma, o));
}

const FaceDetection* followedHead(std::span<const FaceDetection> faces, bool region,
                                  float rememberedLuma, const DetectorOptions& o) {
  const auto mayBeHead = [&](const FaceDetection& f) {
    return (f.insideZone || !region) && !muchDarkerThanHead(f, rememberedLuma, o);
  };
  const FaceDetection* best = nullptr;
  for (const FaceDetection& f : faces) {
    if (!mayBeHead(f) || (best && f.width <= best->width)) continue;
    bool onAnother = false;
    for (const FaceDetection& g : faces)
      onAnother = onAnother || (mayBeHead(g) && faceOnTheBody(f, g, o));
    if (!onAnother) best = &f;
  }
  return best;
}

}  // namespace horopter::detail
