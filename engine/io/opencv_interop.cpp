#include <string>

#include "horopter/core/error.hpp"
#include "horopter/vision/opencv.hpp"

namespace horopter {

namespace {

PixelType pixelTypeOf(const cv::Mat& mat) {
  switch (mat.type()) {
    case CV_8UC1:
      return PixelType::U8C1;
    case CV_8UC3:
      return PixelType::U8C3;
    case CV_16SC1:
      return PixelType::S16C1;
    default:
      throw Error("cv::Mat of type " + cv::typeToString(mat.type()) +
                  " is not supported: use CV_8UC1, CV_8UC3 or CV_16SC1");
  }
}

int cvTypeOf(PixelType type) {
  switch (type) {
    case PixelType::U8C1:
      return CV_8UC1;
    case PixelType::U8C3:
      return CV_8UC3;
    case PixelType::S16C1:
      return CV_16SC1;
  }
  return CV_8UC1;
}

}  // namespace

ConstImageView viewOf(const cv::Mat& mat) {
  if (mat.empty()) throw Error("cv::Mat is empty: load or create the image first");
  if (mat.dims != 2) throw Error("cv::Mat must be two-dimensional");
  return {mat.data, mat.cols, mat.rows, static_cast<std::ptrdiff_t>(mat.step[0]), pixelTypeOf(mat)};
}

ImageView mutableViewOf(cv::Mat& mat) {
  const ConstImageView v = viewOf(mat);
  return {mat.data, v.width, v.height, v.strideBytes, v.type};
}

cv::Mat matOf(const ConstImageView& view) {
  if (view.empty()) return {};
  return cv::Mat(view.height, view.width, cvTypeOf(view.type), const_cast<void*>(view.data),
                 static_cast<std::size_t>(view.strideBytes));
}

cv::Mat matOf(const ImageView& view) {
  return matOf(static_cast<ConstImageView>(view));
}

}  // namespace horopter
