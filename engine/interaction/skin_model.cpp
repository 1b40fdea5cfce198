// The chroma lookup table of the skin model; see horopter/interaction/skin_model.hpp.
#include "horopter/interaction/skin_model.hpp"

#include <opencv2/imgproc.hpp>

#include "horopter/core/error.hpp"

namespace horopter {

SkinModel::SkinModel(const SkinThresholds& t) : table_(256 * 256, 0), yMin_(t.yMin) {
  if (t.crMin > t.crMax || t.cbMin > t.cbMax || t.crMin < 0 || t.crMax > 255 || t.cbMin < 0 ||
      t.cbMax > 255)
    throw Error("skin thresholds need 0 <= min <= max <= 255 for Cr and Cb");
  for (int cr = t.crMin; cr <= t.crMax; ++cr)
    for (int cb = t.cbMin; cb <= t.cbMax; ++cb)
      table_[static_cast<std::size_t>(cr * 256 + cb)] = 1;
}

SkinModel SkinModel::train(const std::vector<cv::Mat>& bgr, const std::vector<cv::Mat>& labels,
                           double threshold) {
  if (bgr.empty() || bgr.size() != labels.size())
    throw Error(
        "skin model training needs as many label images as colour images (and at least one)");
  if (!(threshold > 0 && threshold < 1))
    throw Error("skin model threshold must be a probability in (0, 1)");
  cv::Mat skin = cv::Mat::zeros(256, 256, CV_32F), other = cv::Mat::zeros(256, 256, CV_32F);
  int darkest = 255;
  for (std::size_t i = 0; i < bgr.size(); ++i) {
    if (bgr[i].type() != CV_8UC3 || labels[i].type() != CV_8UC1 ||
        bgr[i].size() != labels[i].size())
      throw Error("skin model training image " + std::to_string(i) +
                  ": colour must be CV_8UC3 and labels CV_8UC1 of the same size");
    cv::Mat ycrcb;
    cv::cvtColor(bgr[i], ycrcb, cv::COLOR_BGR2YCrCb);
    for (int y = 0; y < ycrcb.rows; ++y) {
      const auto* p = ycrcb.ptr<cv::Vec3b>(y);
      const auto* l = labels[i].ptr<std::uint8_t>(y);
      for (int x = 0; x < ycrcb.cols; ++x) {
        if (l[x] == 255) {
          skin.at<float>(p[x][1], p[x][2]) += 1;
          darkest = std::min<int>(darkest, p[x][0]);
        } else if (l[x] == 0) {
          other.at<float>(p[x][1], p[x][2]) += 1;
        }
      }
    }
  }
  const double skinCount = cv::sum(skin)[0], otherCount = cv::sum(other)[0];
  if (skinCount == 0 || otherCount == 0)
    throw Error("skin model training needs both skin (255) and non-skin (0) labelled pixels");
  // Class-conditional densities, smoothed, then the posterior with equal priors.
  cv::blur(skin, skin, cv::Size(5, 5));
  cv::blur(other, other, cv::Size(5, 5));
  skin /= skinCount;
  other /= otherCount;
  SkinModel model;
  model.yMin_ = darkest;
  for (int cr = 0; cr < 256; ++cr)
    for (int cb = 0; cb < 256; ++cb) {
      const double s = skin.at<float>(cr, cb), o = other.at<float>(cr, cb);
      model.table_[static_cast<std::size_t>(cr * 256 + cb)] =
          (s > 0 && s / (s + o) > threshold) ? 1 : 0;
    }
  return model;
}

bool SkinModel::isSkinBgr(const cv::Vec3b& bgr) const {
  cv::Mat one(1, 1, CV_8UC3, cv::Scalar(bgr[0], bgr[1], bgr[2])), ycrcb;
  cv::cvtColor(one, ycrcb, cv::COLOR_BGR2YCrCb);
  const cv::Vec3b v = ycrcb.at<cv::Vec3b>(0, 0);
  return isSkin(v[0], v[1], v[2]);
}

void SkinModel::classify(const cv::Mat& bgr, const cv::Rect& roi, cv::Mat& out) const {
  if (bgr.type() != CV_8UC3) throw Error("skin classification needs a BGR (CV_8UC3) image");
  const cv::Rect r = roi & cv::Rect(0, 0, bgr.cols, bgr.rows);
  out.create(r.size(), CV_8UC1);
  if (r.empty()) return;
  cv::Mat ycrcb;
  cv::cvtColor(bgr(r), ycrcb, cv::COLOR_BGR2YCrCb);
  for (int y = 0; y < ycrcb.rows; ++y) {
    const auto* p = ycrcb.ptr<cv::Vec3b>(y);
    auto* o = out.ptr<std::uint8_t>(y);
    for (int x = 0; x < ycrcb.cols; ++x)
      o[x] = isSkin(p[x][0], p[x][1], p[x][2]) ? 255 : 0;
  }
}

}  // namespace horopter
