// The movement overlay for horopter run's annotated output; see
// include/horopter/movement/movement.hpp.
#include <opencv2/imgproc.hpp>

#include <cstdio>
#include <string>

#include "horopter/movement/movement.hpp"

namespace horopter {

void drawMovementOverlay(cv::Mat& bgr, const MovementState& state) {
  if (bgr.empty() || bgr.type() != CV_8UC3) return;
  const int barW = 90, rowH = 14, pad = 6;
  const int boxW = 110 + barW + 2 * pad, boxH = (kMovementClassCount + 3) * rowH + 2 * pad;
  const cv::Rect box(std::max(0, bgr.cols - boxW), 0, std::min(boxW, bgr.cols),
                     std::min(boxH, bgr.rows));
  cv::Mat roi = bgr(box);
  roi *= 0.4;  // darken behind the text
  const auto font = cv::FONT_HERSHEY_SIMPLEX;
  const double scale = 0.38;
  const cv::Scalar white(255, 255, 255), green(80, 220, 80), yellow(60, 220, 240);
  int y = pad + rowH - 3;
  auto text = [&](const std::string& s, int x, const cv::Scalar& colour) {
    cv::putText(bgr, s, {box.x + x, y}, font, scale, colour, 1, cv::LINE_AA);
  };
  text(std::string("movement: ") + movementClassName(state.likeliest), pad, white);
  y += rowH;
  for (int m = 0; m < kMovementClassCount; ++m) {
    const bool top = static_cast<int>(state.likeliest) == m;
    text(movementClassName(static_cast<MovementClass>(m)), pad, top ? green : white);
    const int w = static_cast<int>(state.posterior[m] * barW + 0.5);
    cv::rectangle(bgr, cv::Rect(box.x + pad + 100, y - rowH + 5, std::max(1, w), rowH - 4),
                  top ? green : white, cv::FILLED);
    y += rowH;
  }
  char buf[96];
  std::snprintf(buf, sizeof buf, "action: %s%s", robotActionName(state.action),
                state.interactionStopped ? " (stopped)" : "");
  text(buf, pad, yellow);
  y += rowH;
  std::snprintf(buf, sizeof buf, "base %.2f m/s %.2f rad/s", state.base.linear, state.base.angular);
  text(buf, pad, yellow);
}

}  // namespace horopter
