#include "run_annotation.hpp"

#include <algorithm>
#include <cstdio>
#include <opencv2/imgproc.hpp>

#include "horopter/app/robot_stage.hpp"
#include "horopter/core/error.hpp"
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
// putText was most of the annotation's time.) `shrink`: the view is drawn
// at 1/shrink of its full size.
void label(cv::Mat& image, const std::string& text, int line, int shrink = 1) {
  constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
  const double fontScale = 0.55 / shrink;
  int baseline = 0;
  const cv::Size extent = cv::getTextSize(text, kFont, fontScale, 1, &baseline);
  const cv::Point at(8 / shrink, (22 + 22 * line) / shrink);
  const cv::Rect band =
      cv::Rect(at.x - 4, at.y - extent.height - 4, extent.width + 8, extent.height + baseline + 6) &
      cv::Rect(0, 0, image.cols, image.rows);
  if (!band.empty()) {
    cv::Mat under = image(band);
    under.convertTo(under, -1, 0.35);
  }
  cv::putText(image, text, at, kFont, fontScale, cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
}

// Faces (green boxes), hand candidates (cyan rings), the subject's tracks
// (head H, the person's own left L and right R hands; filled when observed
// this frame, hollow when coasting) and the body triangle with its incentre,
// on an image 1/shrink of the frame's size.
void drawPeople(cv::Mat& image, const Frame& frame, int shrink) {
  const float k = 1.0F / static_cast<float>(shrink);
  auto at = [k](cv::Point2f p) { return p * k; };
  auto px = [shrink](int length) { return std::max(1, length / shrink); };
  if (frame.detections) {
    for (const FaceDetection& f : frame.detections->faces) {
      const cv::Rect box(f.box.x / shrink, f.box.y / shrink, f.box.width / shrink,
                         f.box.height / shrink);
      cv::rectangle(image, box, f.insideZone ? cv::Scalar(0, 220, 0) : cv::Scalar(0, 120, 0),
                    px(2));
    }
    for (const HandDetection& h : frame.detections->hands)
      cv::circle(image, at(h.centroid), px(6), cv::Scalar(255, 255, 0), 1, cv::LINE_AA);
  }
  if (!frame.tracking) return;
  const TrackingState& t = *frame.tracking;
  const cv::Scalar colour =
      t.election == ElectionState::Godfather ? cv::Scalar(255, 0, 255) : cv::Scalar(0, 165, 255);
  if (t.triangle) {
    const cv::Point2f v[3] = {at(t.triangle->head), at(t.triangle->leftHand),
                              at(t.triangle->rightHand)};
    for (int i = 0; i < 3; ++i)
      cv::line(image, v[i], v[(i + 1) % 3], colour, 1, cv::LINE_AA);
    cv::circle(image, at(t.triangle->incentre), px(4), colour, cv::FILLED, cv::LINE_AA);
  }
  const std::pair<const PartState*, const char*> parts[] = {
      {&t.head, "H"}, {&t.leftHand, "L"}, {&t.rightHand, "R"}};
  for (const auto& [part, name] : parts) {
    if (!part->tracked) continue;
    cv::circle(image, at(part->image), px(9), colour, part->observed ? cv::FILLED : px(2),
               cv::LINE_AA);
    cv::putText(image, name, at(part->image + cv::Point2f(10, -10)), cv::FONT_HERSHEY_SIMPLEX,
                0.6 / shrink, colour, px(2), cv::LINE_AA);
  }
}

}  // namespace

cv::Mat annotateFrame(const Frame& frame, const StereoParams& params, double fps, int shrink) {
  if (shrink < 1) throw Error("the annotated view's shrink factor must be at least 1");
  const cv::Size fullSize = frame.left.size();
  const cv::Size size(fullSize.width / shrink, fullSize.height / shrink);
  if (size.width < 1 || size.height < 1) throw Error("the frame is too small for this shrink");
  // Drawn at the size it is shown: the image panels' pixels cost a
  // shrink-squared less, and a video frame needs no resize afterwards.
  cv::Mat left = frame.left, disparity = frame.disparity, mask = frame.mask;
  if (shrink > 1) {
    cv::resize(frame.left, left, size, 0, 0, cv::INTER_AREA);
    if (disparity.size() == fullSize)
      cv::resize(frame.disparity, disparity, size, 0, 0, cv::INTER_NEAREST);
    if (mask.size() == fullSize) cv::resize(frame.mask, mask, size, 0, 0, cv::INTER_NEAREST);
  }
  left = asBgr(left);  // after shrinking: a grey image is converted at the shown size
  // Not cleared as a whole: every panel is painted below (filling the
  // mosaic cost a tenth of drawing it).
  const cv::Scalar background(24, 24, 24);
  cv::Mat mosaic(size.height * 2, size.width * 2, CV_8UC3);

  cv::Mat topLeft = mosaic(cv::Rect(0, 0, size.width, size.height));
  left.copyTo(topLeft);
  if (mask.size() == size) {
    const cv::Rect roi = cv::boundingRect(mask);
    if (roi.area() > 0)
      cv::rectangle(topLeft, roi, cv::Scalar(0, 255, 255), std::max(1, 2 / shrink));
  }
  drawPeople(topLeft, frame, shrink);
  label(topLeft, "left, zone ROI", 0, shrink);

  cv::Mat topRight = mosaic(cv::Rect(size.width, 0, size.width, size.height));
  if (disparity.size() == size) {
    colorizeDisparityInto(viewOf(disparity), params, topRight);
    drawDisparityScale(topRight, params, shrink);
  } else {
    topRight.setTo(background);
  }
  label(topRight, "disparity (near red, far blue)", 0, shrink);

  cv::Mat bottomLeft = mosaic(cv::Rect(0, size.height, size.width, size.height));
  left.convertTo(bottomLeft, -1, 0.25);  // what `left * 0.25` does, without its image
  if (mask.size() == size) left.copyTo(bottomLeft, mask);
  label(bottomLeft, "inside the horopter", 0, shrink);

  // The text panel is drawn at full size and then shrunk: its overlays have
  // fixed sizes, and small text drawn directly reads worse.
  cv::Mat shownPanel = mosaic(cv::Rect(size.width, size.height, size.width, size.height));
  cv::Mat panel = shrink > 1 ? cv::Mat(fullSize, CV_8UC3) : shownPanel;
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
  if (shrink > 1) cv::resize(panel, shownPanel, shownPanel.size(), 0, 0, cv::INTER_AREA);
  return mosaic;
}

}  // namespace horopter::cli
