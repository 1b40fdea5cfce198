// Texture sampling against the plainest form of its specification: each
// mipmap level built as the Texture does, floor by std::floor, wrap by %,
// the level's scale by std::ldexp, bilinear channel by channel. The same
// float operations in the same order, so the colours must be bit-identical,
// for power-of-two sides (the masked wrap) and for others (the % wrap).
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "synthetic/textures.hpp"

namespace horopter::synth {
namespace {

std::vector<cv::Mat> referenceLevels(const cv::Mat& bgr8) {
  std::vector<cv::Mat> levels;
  cv::Mat level;
  bgr8.convertTo(level, CV_32FC3);
  levels.push_back(level);
  while (levels.size() < 8 && level.cols >= 16 && level.rows >= 16) {
    cv::Mat down;
    cv::pyrDown(level, down);
    levels.push_back(down);
    level = down;
  }
  return levels;
}

int referenceWrap(int i, int n) {
  const int r = i % n;
  return r < 0 ? r + n : r;
}

cv::Vec3f referenceLevelSample(const cv::Mat& img, int level, double u, double v, bool wrap) {
  const double scale = std::ldexp(1.0, -level);
  u = u * scale - 0.5;
  v = v * scale - 0.5;
  const int w = img.cols, h = img.rows;
  int x0, y0, x1, y1;
  float fx, fy;
  if (wrap) {
    const int iu = static_cast<int>(std::floor(u)), iv = static_cast<int>(std::floor(v));
    fx = static_cast<float>(u - iu);
    fy = static_cast<float>(v - iv);
    x0 = referenceWrap(iu, w);
    y0 = referenceWrap(iv, h);
    x1 = referenceWrap(x0 + 1, w);
    y1 = referenceWrap(y0 + 1, h);
  } else {
    u = std::min(std::max(u, 0.0), w - 1.0);
    v = std::min(std::max(v, 0.0), h - 1.0);
    x0 = static_cast<int>(u);
    y0 = static_cast<int>(v);
    x1 = std::min(x0 + 1, w - 1);
    y1 = std::min(y0 + 1, h - 1);
    fx = static_cast<float>(u - x0);
    fy = static_cast<float>(v - y0);
  }
  const cv::Vec3f a = img.at<cv::Vec3f>(y0, x0), b = img.at<cv::Vec3f>(y0, x1);
  const cv::Vec3f c = img.at<cv::Vec3f>(y1, x0), d = img.at<cv::Vec3f>(y1, x1);
  const float gx = 1 - fx, gy = 1 - fy;
  cv::Vec3f out;
  for (int k = 0; k < 3; ++k) {
    const float top = a[k] * gx + b[k] * fx;
    const float bottom = c[k] * gx + d[k] * fx;
    out[k] = top * gy + bottom * fy;
  }
  return out;
}

// The level of detail as Texture::sample takes it (fastLog2 is part of
// what is specified, so it is not replaced here).
double referenceLod(double footprint) {
  if (footprint <= 1) return 0.0;
  std::uint64_t bits;
  std::memcpy(&bits, &footprint, sizeof bits);
  const int e = static_cast<int>((bits >> 52) & 0x7FF) - 1023;
  bits = (bits & 0x000FFFFFFFFFFFFFull) | 0x3FF0000000000000ull;
  double m;
  std::memcpy(&m, &bits, sizeof m);
  return e + (m - 1);
}

cv::Vec3f referenceSample(const std::vector<cv::Mat>& levels, double u, double v, double footprint,
                          bool wrap) {
  const int last = static_cast<int>(levels.size()) - 1;
  const double lod = referenceLod(footprint);
  if (lod <= 0) return referenceLevelSample(levels[0], 0, u, v, wrap);
  if (lod >= last) return referenceLevelSample(levels[last], last, u, v, wrap);
  const int l0 = static_cast<int>(lod);
  const float f = static_cast<float>(lod - l0);
  const cv::Vec3f a = referenceLevelSample(levels[l0], l0, u, v, wrap);
  const cv::Vec3f b = referenceLevelSample(levels[l0 + 1], l0 + 1, u, v, wrap);
  const float g = 1 - f;
  return {a[0] * g + b[0] * f, a[1] * g + b[1] * f, a[2] * g + b[2] * f};
}

bool sameBits(const cv::Vec3f& a, const cv::Vec3f& b) {
  return std::memcmp(a.val, b.val, sizeof a.val) == 0;
}

TEST(SyntheticTextureSampling, BitIdenticalToThePlainestSampler) {
  std::mt19937 rng(11);
  // Power-of-two sides, neither, and one of each.
  const cv::Size sizes[] = {{256, 256}, {48, 40}, {64, 40}, {37, 128}, {8, 8}};
  for (const cv::Size& size : sizes) {
    cv::Mat bgr8(size, CV_8UC3);
    cv::randu(bgr8, cv::Scalar::all(0), cv::Scalar::all(256));
    const Texture tex(bgr8);
    const std::vector<cv::Mat> levels = referenceLevels(bgr8);
    std::uniform_real_distribution<double> coord(-3000, 3000), logFootprint(-2, 10);
    int wrapMismatches = 0, clampMismatches = 0;
    for (int n = 0; n < 20000; ++n) {
      double u = coord(rng), v = coord(rng);
      if (n % 7 == 0) u = std::round(u);  // integers and half-integers
      if (n % 11 == 0) v = std::round(v) + 0.5;
      const double footprint = std::exp2(logFootprint(rng));
      wrapMismatches += !sameBits(tex.sampleWrap(u, v, footprint),
                                  referenceSample(levels, u, v, footprint, true));
      clampMismatches += !sameBits(tex.sampleClamp(u, v, footprint),
                                   referenceSample(levels, u, v, footprint, false));
    }
    EXPECT_EQ(wrapMismatches, 0) << size;
    EXPECT_EQ(clampMismatches, 0) << size;
  }
}

}  // namespace
}  // namespace horopter::synth
