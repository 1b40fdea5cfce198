#include "geometry/zone_figure.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>

namespace horopter {

namespace {

// World (x, z) in the baseline's unit -> canvas pixels, z upwards.
struct View {
  double scale, x0, zTop;
  cv::Point operator()(double x, double z) const {
    return {static_cast<int>(std::lround((x - x0) * scale)),
            static_cast<int>(std::lround((zTop - z) * scale))};
  }
};

// A "nice" length (1, 2 or 5 times a power of ten) near `target`.
double niceLength(double target) {
  const double p = std::pow(10.0, std::floor(std::log10(target)));
  for (double m : {5.0, 2.0, 1.0})
    if (m * p <= target) return m * p;
  return p;
}

}  // namespace

cv::Mat drawZoneTopDown(const RectifiedGeometry& g, int width, const ViethMuellerCircle& c,
                        int canvasPx) {
  const double b = g.baseline;
  const double far = 1.15 * std::max({c.centreZ + c.radius, c.fixation.y(), 4 * b});
  const double half = std::max({1.15 * c.radius, 0.55 * far, 2 * b});
  const double zBottom = -0.08 * far;
  const double scale = canvasPx / std::max(2 * half, far - zBottom);
  const View v{scale, -half, far};
  const int rows = static_cast<int>(std::lround((far - zBottom) * scale));
  cv::Mat img(rows, static_cast<int>(std::lround(2 * half * scale)), CV_8UC3,
              cv::Scalar(255, 255, 255));

  // The zone: the circle's inside in front of the baseline.
  const int radiusPx = static_cast<int>(std::lround(c.radius * scale));
  cv::circle(img, v(0, c.centreZ), radiusPx, cv::Scalar(200, 240, 200), cv::FILLED, cv::LINE_AA);
  cv::rectangle(img, v(-half, 0), cv::Point(img.cols, img.rows), cv::Scalar(255, 255, 255),
                cv::FILLED);
  cv::circle(img, v(0, c.centreZ), radiusPx, cv::Scalar(40, 140, 40), 2, cv::LINE_AA);
  cv::line(img, v(-half, 0), v(half, 0), cv::Scalar(210, 210, 210), 1);

  // Fields of view (edge columns 0 and width-1) and rectified optical axes.
  const double reach = 4 * (far + half);
  for (double cam : {-0.5 * b, 0.5 * b}) {
    for (double u : {0.0, static_cast<double>(width - 1)}) {
      const double t = (u - g.cx) / g.focalPx;
      cv::line(img, v(cam, 0), v(cam + reach * t, reach), cv::Scalar(220, 160, 80), 1, cv::LINE_AA);
    }
    cv::line(img, v(cam, 0), v(cam, reach), cv::Scalar(230, 200, 170), 1, cv::LINE_AA);
  }
  // Visual axes to the fixation, the fixation point, the cameras.
  const cv::Point fix = v(c.fixation.x(), c.fixation.y());
  for (double cam : {-0.5 * b, 0.5 * b})
    cv::line(img, v(cam, 0), fix, cv::Scalar(60, 60, 220), 1, cv::LINE_AA);
  cv::circle(img, fix, 6, cv::Scalar(0, 0, 220), cv::FILLED, cv::LINE_AA);
  for (double cam : {-0.5 * b, 0.5 * b}) {
    const cv::Point p = v(cam, 0);
    const std::vector<cv::Point> tri{p + cv::Point(0, -8), p + cv::Point(-7, 6),
                                     p + cv::Point(7, 6)};
    cv::fillConvexPoly(img, tri, cv::Scalar(160, 60, 0), cv::LINE_AA);
  }

  // Labels and a scale bar.
  char text[160];
  const auto put = [&](const char* s, cv::Point at, cv::Scalar colour) {
    cv::putText(img, s, at, cv::FONT_HERSHEY_SIMPLEX, 0.5, colour, 1, cv::LINE_AA);
  };
  std::snprintf(text, sizeof text, "fixation (%.3f, %.3f)", c.fixation.x(), c.fixation.y());
  put(text, fix + cv::Point(10, -8), cv::Scalar(0, 0, 200));
  std::snprintf(text, sizeof text, "Vieth-Mueller circle: centre z %.3f, radius %.3f", c.centreZ,
                c.radius);
  put(text, {10, 20}, cv::Scalar(40, 120, 40));
  std::snprintf(text, sizeof text, "baseline %.4f, focal %.1f px, %d px wide", b, g.focalPx, width);
  put(text, {10, 40}, cv::Scalar(90, 90, 90));
  const double bar = niceLength(0.25 * 2 * half);
  const cv::Point b0(10, img.rows - 12);
  const cv::Point b1 = b0 + cv::Point(static_cast<int>(std::lround(bar * scale)), 0);
  cv::line(img, b0, b1, cv::Scalar(0, 0, 0), 2);
  std::snprintf(text, sizeof text, "%g (unit of the calibration)", bar);
  put(text, b0 + cv::Point(0, -6), cv::Scalar(0, 0, 0));
  return img;
}

}  // namespace horopter
