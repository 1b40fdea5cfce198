// horopter run's annotated view: drawn at the video's size it has the
// video's size and looks like the full view shrunk (the same panels, the
// zone and the boxes in the same places), and an absurd shrink is refused.
#include <gtest/gtest.h>

#include <memory>
#include <opencv2/imgproc.hpp>

#include "horopter/core/error.hpp"
#include "horopter/interaction/detection.hpp"
#include "run_annotation.hpp"

namespace horopter::cli {
namespace {

// A 640x480 frame: a textured left image, a disparity that grows to the
// right, a zone rectangle and a face in it.
Frame sampleFrame() {
  Frame f;
  f.index = 12;
  f.left.create(480, 640, CV_8UC3);
  cv::randu(f.left, 40, 200);
  cv::GaussianBlur(f.left, f.left, cv::Size(9, 9), 3);
  f.disparity.create(480, 640, CV_16SC1);
  for (int y = 0; y < f.disparity.rows; ++y)
    for (int x = 0; x < f.disparity.cols; ++x)
      f.disparity.at<std::int16_t>(y, x) = static_cast<std::int16_t>(x * 64 * 16 / 640);
  f.mask = cv::Mat::zeros(480, 640, CV_8UC1);
  f.mask(cv::Rect(200, 100, 240, 300)).setTo(255);
  auto detections = std::make_shared<Detections>();
  FaceDetection face;
  face.box = cv::Rect(280, 120, 80, 80);
  face.insideZone = true;
  detections->faces.push_back(face);
  f.detections = detections;
  return f;
}

double meanAbsDifference(const cv::Mat& a, const cv::Mat& b) {
  cv::Mat diff;
  cv::absdiff(a, b, diff);
  const cv::Scalar m = cv::mean(diff);
  return (m[0] + m[1] + m[2]) / 3;
}

TEST(RunAnnotation, AViewForTheVideoHasItsSizeAndLooksLikeTheFullViewShrunk) {
  const Frame f = sampleFrame();
  const StereoParams params;
  const cv::Mat full = annotateFrame(f, params, 30, 1);
  ASSERT_EQ(full.size(), cv::Size(1280, 960));
  const cv::Mat half = annotateFrame(f, params, 30, 2);
  ASSERT_EQ(half.size(), cv::Size(640, 480));
  cv::Mat fullShrunk;
  cv::resize(full, fullShrunk, half.size(), 0, 0, cv::INTER_AREA);
  // Each panel apart: edges and text differ by a level or two, a panel
  // drawn elsewhere or at the wrong scale by tens.
  for (const cv::Rect panel : {cv::Rect(0, 0, 320, 240), cv::Rect(320, 0, 320, 240),
                               cv::Rect(0, 240, 320, 240), cv::Rect(320, 240, 320, 240)}) {
    const double d = meanAbsDifference(half(panel), fullShrunk(panel));
    EXPECT_LT(d, 2.0) << "panel at " << panel.x << "," << panel.y;
  }
  // The measure tells a misplaced zone: the same frame with the zone moved
  // 200 px left is far from the full view's.
  Frame shifted = sampleFrame();
  shifted.mask = cv::Mat::zeros(480, 640, CV_8UC1);
  shifted.mask(cv::Rect(0, 100, 240, 300)).setTo(255);
  const cv::Mat wrong = annotateFrame(shifted, params, 30, 2);
  const cv::Rect bottomLeft(0, 240, 320, 240);
  EXPECT_GT(meanAbsDifference(wrong(bottomLeft), fullShrunk(bottomLeft)), 10.0);
}

TEST(RunAnnotation, AShrinkBelowOneOrLargerThanTheFrameIsRefused) {
  const Frame f = sampleFrame();
  EXPECT_THROW(annotateFrame(f, StereoParams(), 30, 0), Error);
  EXPECT_THROW(annotateFrame(f, StereoParams(), 30, 1000), Error);
}

}  // namespace
}  // namespace horopter::cli
