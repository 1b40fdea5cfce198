// cv::Mat interop: views over Mat memory (no copies) and back.
#pragma once

#include "horopter/core/export.hpp"

#include <opencv2/core.hpp>

#include "horopter/core/image.hpp"

namespace horopter {

// A view of `mat` (CV_8UC1, CV_8UC3 or CV_16SC1); throws horopter::Error for
// other types. The Mat must outlive the view.
HOROPTER_API ConstImageView viewOf(const cv::Mat& mat);
HOROPTER_API ImageView mutableViewOf(cv::Mat& mat);

// A cv::Mat header over the view's memory (no copy).
HOROPTER_API cv::Mat matOf(const ConstImageView& view);
HOROPTER_API cv::Mat matOf(const ImageView& view);
inline cv::Mat matOf(const Image& image) {
  return matOf(image.view());
}

}  // namespace horopter
