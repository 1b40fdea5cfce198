// A shirt of skin's colour; see shirt_skin.hpp.
#include "shirt_skin.hpp"

#include <array>
#include <cmath>

namespace horopter::detail {

cv::Rect torsoBox(const FaceDetection& head, const DetectorOptions& o) {
  const double w = head.width;
  const double half = o.shirtSampleHalfWidthFaces * w;
  const double top = head.centre.y + o.shirtSampleTopFaces * w;
  const double bottom = head.centre.y + o.shirtSampleBottomFaces * w;
  return cv::Rect(cv::Point(static_cast<int>(std::lround(head.centre.x - half)),
                            static_cast<int>(std::lround(top))),
                  cv::Point(static_cast<int>(std::lround(head.centre.x + half)),
                            static_cast<int>(std::lround(bottom))));
}

TorsoSample sampleTorso(const cv::Mat& skin, const cv::Mat& grey, const cv::Rect& roi,
                        const FaceDetection& head, const DetectorOptions& o) {
  TorsoSample s;
  if (!(head.width > 0)) return s;
  const cv::Rect box = (torsoBox(head, o) & roi) - roi.tl();
  if (box.empty()) return s;
  std::array<int, 256> histogram{};
  int skinPixels = 0;
  for (int y = box.y; y < box.y + box.height; ++y) {
    const auto* k = skin.ptr<std::uint8_t>(y);
    const auto* g = grey.ptr<std::uint8_t>(y);
    for (int x = box.x; x < box.x + box.width; ++x)
      if (k[x]) {
        ++histogram[g[x]];
        ++skinPixels;
      }
  }
  s.pixels = box.area();
  s.skinFraction = static_cast<float>(skinPixels) / static_cast<float>(s.pixels);
  // The median: a hand held before the chest is a minority of the box.
  int below = 0;
  for (int level = 0; level < 256 && skinPixels > 0; ++level) {
    below += histogram[static_cast<std::size_t>(level)];
    if (2 * below >= skinPixels) {
      s.skinLuma = static_cast<float>(level);
      break;
    }
  }
  return s;
}

float clothLumaBelow(const TorsoSample& torso, float faceLuma, const DetectorOptions& o) {
  const bool skinColoured =
      torso.pixels > 0 && torso.skinLuma > 0 && torso.skinFraction >= o.shirtSkinFraction;
  const bool darkerThanFace = faceLuma > 0 && torso.skinLuma < o.shirtDarkerThanFace * faceLuma;
  if (!(o.shirtLumaOfTorso > 0) || !skinColoured || !darkerThanFace) return 0;
  return static_cast<float>(o.shirtLumaOfTorso * torso.skinLuma);
}

}  // namespace horopter::detail
