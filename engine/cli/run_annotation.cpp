#include "run_annotation.hpp"

#include <cstdio>
#include <opencv2/imgproc.hpp>

#include "horopter/app/robot_stage.hpp"
#include "horopter/interaction/detection.hpp"
#include "horopter/interaction/tracking.hpp"
#include "horopter/movement/movement.hpp"
#include "horopter/sim/sim_frame.hpp"
#include "horopter/sim/synthetic_scene.hpp"
#include "horopter/vision/opencv.hpp"
#include "io/disparity_images.hpp"

namespace horopter::cli {

namespace {

cv::Mat asBgr(const cv::Mat& image) {
  if (image.channels() == 3) return image;
  cv::Mat bgr;
  cv::cvtColor(image, bgr, cv::COLOR_GRAY2BGR);
  return bgr;
}

// White text on a darkened band, readable over any image. (A black outline
// drawn as a second, thick antialiased stroke cost three times as much:
// putText was most of the annotation's time.)
void label(cv::Mat& image, const std::string& text, int line) {
  constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
  constexpr double kScale = 0.55;
  int baseline = 0;
  const cv::Size extent = cv::getTextSize(text, kFont, kScale, 1, &baseline);
  const cv::Point at(8, 22 + 22 * line);
  const cv::Rect band =
      cv::Rect(at.x - 4, at.y - extent.height - 4, extent.width + 8, extent.height + baseline + 6) &
      cv::Rect(0, 0, image.cols, image.rows);
  if (!band.empty()) {
    cv::Mat under = image(band);
    under.convertTo(under, -1, 0.35);
  }
  cv::putText(image, text, at, kFont, kScale, cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
}

// Faces (green boxes), hand candidates (cyan rings), the subject's tracks
// (head H, the person's own left L and right R hands; filled when observed
// this frame, hollow when coasting) and the body triangle with its incentre.
void drawPeople(cv::Mat& image, const Frame& frame) {
  if (frame.detections) {
    for (const FaceDetection& f : frame.detections->faces)
      cv::rectangle(image, f.box, f.insideZone ? cv::Scalar(0, 220, 0) : cv::Scalar(0, 120, 0), 2);
    for (const HandDetection& h : frame.detections->hands)
      cv::circle(image, h.centroid, 6, cv::Scalar(255, 255, 0), 1, cv::LINE_AA);
  }
  if (!frame.tracking) return;
  const TrackingState& t = *frame.tracking;
  const cv::Scalar colour =
      t.election == ElectionState::Godfather ? cv::Scalar(255, 0, 255) : cv::Scalar(0, 165, 255);
  if (t.triangle) {
    const cv::Point2f v[3] = {t.triangle->head, t.triangle->leftHand, t.triangle->rightHand};
    for (int i = 0; i < 3; ++i)
      cv::line(image, v[i], v[(i + 1) % 3], colour, 1, cv::LINE_AA);
    cv::circle(image, t.triangle->incentre, 4, colour, cv::FILLED, cv::LINE_AA);
  }
  const std::pair<const PartState*, const char*> parts[] = {
      {&t.head, "H"}, {&t.leftHand, "L"}, {&t.rightHand, "R"}};
  for (const auto& [part, name] : parts) {
    if (!part->tracked) continue;
    cv::circle(image, part->image, 9, colour, part->observed ? cv::FILLED : 2, cv::LINE_AA);
    cv::putText(image, name, part->image + cv::Point2f(10, -10), cv::FONT_HERSHEY_SIMPLEX, 0.6,
                colour, 2, cv::LINE_AA);
  }
}

}  // namespace

cv::Mat annotateFrame(const Frame& frame, const StereoParams& params, double fps) {
  const cv::Mat left = asBgr(frame.left);
  const cv::Size size = left.size();
  // Not cleared as a whole: every panel is painted below (filling the
  // mosaic cost a tenth of drawing it).
  const cv::Scalar background(24, 24, 24);
  cv::Mat mosaic(size.height * 2, size.width * 2, CV_8UC3);

  cv::Mat topLeft = mosaic(cv::Rect(0, 0, size.width, size.height));
  left.copyTo(topLeft);
  if (!frame.mask.empty()) {
    const cv::Rect roi = cv::boundingRect(frame.mask);
    if (roi.area() > 0) cv::rectangle(topLeft, roi, cv::Scalar(0, 255, 255), 2);
  }
  drawPeople(topLeft, frame);
  label(topLeft, "left, zone ROI", 0);

  cv::Mat topRight = mosaic(cv::Rect(size.width, 0, size.width, size.height));
  if (frame.disparity.size() == size) {
    colorizeDisparity(viewOf(frame.disparity), params).copyTo(topRight);
    drawDisparityScale(topRight, params);
  } else {
    topRight.setTo(background);
  }
  label(topRight, "disparity (near red, far blue)", 0);

  cv::Mat bottomLeft = mosaic(cv::Rect(0, size.height, size.width, size.height));
  cv::Mat dimmed = left * 0.25;
  dimmed.copyTo(bottomLeft);
  if (!frame.mask.empty()) left.copyTo(bottomLeft, frame.mask);
  label(bottomLeft, "inside the horopter", 0);

  cv::Mat panel = mosaic(cv::Rect(size.width, size.height, size.width, size.height));
  panel.setTo(background);
  char text[160];
  int line = 0;
  std::snprintf(text, sizeof text, "frame %lld   %.0f frames/s",
                static_cast<long long>(frame.index), fps);
  label(panel, text, line++);
  if (!frame.mask.empty()) {
    std::snprintf(text, sizeof text, "inside the zone: %.1f%% of pixels",
                  100.0 * cv::countNonZero(frame.mask) / static_cast<double>(frame.mask.total()));
    label(panel, text, line++);
  }
  if (frame.detections) {
    std::snprintf(text, sizeof text, "detection (%s): %zu face(s), %zu hand candidate(s)",
                  detectionScopeName(frame.detections->scope), frame.detections->faces.size(),
                  frame.detections->hands.size());
    label(panel, text, line++);
  }
  if (frame.tracking) {
    const TrackingState& t = *frame.tracking;
    if (t.election == ElectionState::Candidate)
      std::snprintf(text, sizeof text, "godfather: candidate for %.1f s", t.candidateS);
    else
      std::snprintf(text, sizeof text, "godfather: %s",
                    t.election == ElectionState::Godfather ? "elected" : "none");
    label(panel, text, line++);
    if (t.triangle) {
      std::snprintf(text, sizeof text, "triangle: perimeter %.0f px, head angle %.0f deg",
                    t.triangle->perimeter, t.triangle->headAngleRad * 57.2958);
      label(panel, text, line++);
    }
    if (t.headCommand) {
      std::snprintf(text, sizeof text, "head command: pan %.1f tilt %.1f deg (at frame %lld)",
                    t.headCommand->pan * 57.2958, t.headCommand->tilt * 57.2958,
                    static_cast<long long>(t.headCommandFrame));
      label(panel, text, line++);
    }
  }
  if (const synth::FrameTruth* truth = sim::truthOf(frame)) {
    std::snprintf(text, sizeof text, "head pan %.1f tilt %.1f deg, fixation %.2f m",
                  truth->head.pan * 57.2958, truth->head.tilt * 57.2958, truth->fixationDistanceM);
    label(panel, text, line++);
    for (const auto& person : truth->people) {
      std::snprintf(text, sizeof text, "person %d: %s, %s", person.id,
                    person.insideZone ? "inside" : "outside", synth::movementName(person.movement));
      label(panel, text, line++);
    }
  }
  // The movement and robot boxes below the text lines, which run wide.
  cv::Mat lower = panel(cv::Rect(0, panel.rows / 2, panel.cols, panel.rows - panel.rows / 2));
  if (frame.movement) drawMovementOverlay(lower, *frame.movement);
  if (frame.robot) drawRobotOverlay(lower, *frame.robot);
  return mosaic;
}

}  // namespace horopter::cli
