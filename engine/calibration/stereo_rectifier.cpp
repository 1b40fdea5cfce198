// The rectification stage: maps once, a remap per frame into reused buffers.
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <string>

#include "horopter/core/error.hpp"
#include "horopter/vision/calibration.hpp"

namespace horopter {

StereoRectifier::StereoRectifier(const StereoCalibration& c) : size_(c.imageSize) {
  if (size_.empty()) throw Error("calibration has no image size: run horopter calibrate");
  rectifiedGeometry(c);  // throws for a calibration without a usable rectification
  cv::initUndistortRectifyMap(c.K1, c.D1, c.R1, c.P1, size_, CV_16SC2, map1Left_, map2Left_);
  cv::initUndistortRectifyMap(c.K2, c.D2, c.R2, c.P2, size_, CV_16SC2, map1Right_, map2Right_);
}

void StereoRectifier::rectify(const cv::Mat& left, const cv::Mat& right) {
  for (const cv::Mat* m : {&left, &right}) {
    if (m->size() != size_)
      throw Error(std::string(m == &left ? "left" : "right") + " image is " +
                  std::to_string(m->cols) + "x" + std::to_string(m->rows) +
                  " but the calibration is for " + std::to_string(size_.width) + "x" +
                  std::to_string(size_.height) + ": calibrate at the capture resolution");
  }
  cv::remap(left, outLeft_, map1Left_, map2Left_, cv::INTER_LINEAR);
  cv::remap(right, outRight_, map1Right_, map2Right_, cv::INTER_LINEAR);
}

}  // namespace horopter
