// A skin colour model on the chroma plane (Cr, Cb) of YCrCb: a 256 x 256
// lookup table, filled either from calibrated thresholds or trained from
// labelled pixels (a skin / non-skin histogram ratio). Luma is ignored, so a
// change of lighting gain moves skin along the table only a little.
#pragma once

#include "horopter/core/export.hpp"

#include <opencv2/core.hpp>

#include <cstdint>
#include <vector>

namespace horopter {

struct HOROPTER_API SkinThresholds {
  int crMin = 135, crMax = 180;  // Chai and Ngan's classic box, widened a little
  int cbMin = 77, cbMax = 127;
  int yMin = 40;  // darker pixels carry no reliable chroma
};

class HOROPTER_API SkinModel {
 public:
  // The thresholds' box (the default model: SkinThresholds' defaults).
  SkinModel() : SkinModel(SkinThresholds{}) {}
  explicit SkinModel(const SkinThresholds& thresholds);

  // Trains from labelled pixels: `bgr` CV_8UC3 images and `labels` CV_8UC1 of
  // the same size (255 skin, 0 not skin, anything else ignored). A chroma is
  // skin when P(skin | chroma) > `threshold`, with the counts smoothed over a
  // 5x5 chroma neighbourhood. Throws horopter::Error for mismatched or empty
  // inputs, or labels without both classes.
  static SkinModel train(const std::vector<cv::Mat>& bgr, const std::vector<cv::Mat>& labels,
                         double threshold = 0.5);

  bool isSkin(std::uint8_t y, std::uint8_t cr, std::uint8_t cb) const {
    return y >= yMin_ && table_[(static_cast<int>(cr) << 8) | cb] != 0;
  }
  bool isSkinBgr(const cv::Vec3b& bgr) const;

  // 255 where skin, 0 elsewhere, over `roi` of `bgr` (CV_8UC3); `out` is
  // CV_8UC1 of the roi's size.
  void classify(const cv::Mat& bgr, const cv::Rect& roi, cv::Mat& out) const;

 private:
  std::vector<std::uint8_t> table_;  // [cr * 256 + cb]
  int yMin_ = 0;
};

}  // namespace horopter
