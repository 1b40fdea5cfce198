#include "bench_inputs.hpp"

#include <map>
#include <utility>

#include <opencv2/imgproc.hpp>

#include "horopter/vision/geometry.hpp"
#include "horopter/vision/opencv.hpp"

namespace horopter::bench {

namespace {

constexpr std::uint64_t kSeed = 20240601;

// Texture: uniform noise blurred to a grain of a few pixels, stretched back
// to the full 8-bit range so the x-Sobel prefilter sees real contrast.
cv::Mat smoothedNoise(FrameSize size, cv::RNG& rng) {
  cv::Mat noise(size.height, size.width, CV_32F);
  rng.fill(noise, cv::RNG::UNIFORM, 0.0, 1.0);
  cv::GaussianBlur(noise, noise, cv::Size(), 1.5);
  cv::Mat texture;
  cv::normalize(noise, texture, 0, 255, cv::NORM_MINMAX, CV_8U);
  return texture;
}

// The scene's disparity (px) seen at right-view pixel (x, y); the nearest
// surface wins where they overlap. Coordinates are relative to the frame, so
// the layout is the same at every size.
float sceneDisparity(FrameSize size, int x, int y) {
  const double u = (x + 0.5) / size.width;
  const double v = (y + 0.5) / size.height;
  // A disc, nearest, slightly slanted.
  const double du = (u - 0.68) * size.width / size.height;
  const double dv = v - 0.55;
  if (du * du + dv * dv < 0.18 * 0.18) return static_cast<float>(42 + 6 * u);
  // A rectangle, slanted the other way.
  if (u > 0.15 && u < 0.45 && v > 0.2 && v < 0.7) return static_cast<float>(32 - 8 * u);
  // The background, farther towards the top (a ground plane).
  return static_cast<float>(8 + 10 * v);
}

// Flattens a patch of the background in the left view: no texture there,
// so the texture check rejects it.
void addTexturelessPatch(cv::Mat& left) {
  const cv::Rect patch(left.cols * 55 / 100, left.rows * 5 / 100, left.cols * 30 / 100,
                       left.rows * 15 / 100);
  left(patch).setTo(128);
}

}  // namespace

StereoPair makeStereoPair(FrameSize size) {
  cv::RNG rng(kSeed);
  cv::Mat left = smoothedNoise(size, rng);
  addTexturelessPatch(left);

  // The right view samples the left one where the scene puts it:
  // right(x, y) = left(x + d(x, y), y).
  cv::Mat mapX(size.height, size.width, CV_32F);
  cv::Mat mapY(size.height, size.width, CV_32F);
  for (int y = 0; y < size.height; ++y) {
    for (int x = 0; x < size.width; ++x) {
      mapX.at<float>(y, x) = static_cast<float>(x) + sceneDisparity(size, x, y);
      mapY.at<float>(y, x) = static_cast<float>(y);
    }
  }
  cv::Mat right;
  cv::remap(left, right, mapX, mapY, cv::INTER_LINEAR, cv::BORDER_REFLECT_101);

  // Sensor noise on the right view only, so that the views differ by more
  // than the shift and the left patch stays perfectly flat.
  cv::Mat noise(size.height, size.width, CV_16S);
  rng.fill(noise, cv::RNG::NORMAL, 0.0, 2.0);
  cv::Mat noisyRight;
  cv::add(right, noise, noisyRight, cv::noArray(), CV_8U);

  StereoPair pair{Image(size.width, size.height, PixelType::U8C1),
                  Image(size.width, size.height, PixelType::U8C1),
                  Image(size.width, size.height, PixelType::U8C3)};
  // Writing through headers over our buffers keeps their alignment and padding.
  cv::Mat leftOut = matOf(pair.left.view());
  cv::Mat rightOut = matOf(pair.right.view());
  cv::Mat colourOut = matOf(pair.leftColour.view());
  left.copyTo(leftOut);
  noisyRight.copyTo(rightOut);
  cv::cvtColor(left, colourOut, cv::COLOR_GRAY2BGR);
  return pair;
}

std::vector<std::int16_t> sceneThresholds(FrameSize size) {
  RectifiedGeometry geometry;
  geometry.focalPx = size.width;
  geometry.cx = (size.width - 1) / 2.0;
  geometry.baseline = 1.0;  // thresholds in pixels do not depend on the unit
  return horopterThresholds(geometry, size.width,
                            fixationFromDisparity(geometry, geometry.cx, kFixationDisparityPx));
}

const StereoPair& stereoPair(FrameSize size) {
  static std::map<std::pair<int, int>, StereoPair> pairs;
  const std::pair<int, int> key{size.width, size.height};
  auto it = pairs.find(key);
  if (it == pairs.end()) it = pairs.emplace(key, makeStereoPair(size)).first;
  return it->second;
}

}  // namespace horopter::bench
