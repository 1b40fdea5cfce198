#include "naive_reference.hpp"

#include <algorithm>
#include <cstdlib>
#include <deque>
#include <vector>

namespace horopter::test::naive {

std::int64_t floorDiv(std::int64_t a, std::int64_t b) {
  std::int64_t q = a / b;
  if ((a % b != 0) && (a < 0)) --q;
  return q;
}

void prefilterXSobel(const ConstImageView& src, int cap, TestImage& filtered, TestImage& texture) {
  const int w = src.width;
  const int h = src.height;
  filtered = TestImage(w, h, PixelType::U8C1);
  texture = TestImage(w, h, PixelType::U8C1);
  // Reflect-101, written out case by case.
  const auto pixel = [&](int x, int y) -> int {
    int yy = y;
    if (h == 1) {
      yy = 0;
    } else if (y == -1) {
      yy = 1;
    } else if (y == h) {
      yy = h - 2;
    }
    return src.row<std::uint8_t>(yy)[x];
  };
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      int sobel = 0;
      if (x != 0 && x != w - 1) {
        for (int dy = -1; dy <= 1; ++dy) {
          const int weight = dy == 0 ? 2 : 1;
          sobel += weight * (pixel(x + 1, y + dy) - pixel(x - 1, y + dy));
        }
      }
      int c = sobel;
      if (c > cap) c = cap;
      if (c < -cap) c = -cap;
      filtered.at<std::uint8_t>(x, y) = static_cast<std::uint8_t>(c + cap);
      texture.at<std::uint8_t>(x, y) = static_cast<std::uint8_t>(c < 0 ? -c : c);
    }
  }
}

bool inMatchRegion(int x, int y, int width, int height, const StereoParams& params) {
  const int r = params.blockSize / 2;
  if (y - r < 0 || y + r >= height) return false;
  for (int d = params.minDisparity; d < params.minDisparity + params.numDisparities; ++d) {
    // Left window columns x-r..x+r, right window columns x-r-d..x+r-d.
    if (x - r < 0 || x + r >= width) return false;
    if (x - r - d < 0 || x + r - d >= width) return false;
  }
  return true;
}

// The largest disparity pixel (x, y) is matched at: maxD in the region; in
// the left band (params.leftBand = m > 0), a pixel left of the region whose
// window fits the left image and the right image's right edge at every d,
// the largest d whose window fits the right image's left edge, where at
// least m disparities do; minDisparity - 1: not matched.
static int matchedTop(int x, int y, int width, int height, const StereoParams& params) {
  const int r = params.blockSize / 2;
  const int minD = params.minDisparity;
  const int maxD = minD + params.numDisparities - 1;
  if (inMatchRegion(x, y, width, height, params)) return maxD;
  if (params.leftBand == 0 || y - r < 0 || y + r >= height || x - r < 0 || x + r >= width)
    return minD - 1;
  int fitting = 0, top = minD - 1;
  for (int d = minD; d <= maxD; ++d) {
    if (x + r - d >= width) return minD - 1;  // right of the region, not the band
    if (x - r - d >= 0) {
      ++fitting;
      top = d;
    }
  }
  // Left of a region that exists: a band pixel needs one to its right.
  bool regionRight = false;
  for (int xi = x + 1; xi < width && !regionRight; ++xi)
    regionRight = inMatchRegion(xi, y, width, height, params);
  return fitting >= params.leftBand && regionRight ? top : minD - 1;
}

std::int32_t sadCost(const ConstImageView& left, const ConstImageView& right, int x, int y, int d,
                     int radius) {
  std::int32_t sum = 0;
  for (int j = -radius; j <= radius; ++j) {
    for (int i = -radius; i <= radius; ++i) {
      const int l = left.row<std::uint8_t>(y + j)[x + i];
      const int r = right.row<std::uint8_t>(y + j)[x + i - d];
      sum += std::abs(l - r);
    }
  }
  return sum;
}

MatchResult matchBlocks(const ConstImageView& left, const ConstImageView& right,
                        const ConstImageView& texture, const StereoParams& params) {
  const int w = left.width;
  const int h = left.height;
  const int r = params.blockSize / 2;
  const int minD = params.minDisparity;
  const int count = params.numDisparities;
  const int maxD = minD + count - 1;
  const auto invalid = static_cast<std::int16_t>((minD - 1) * 16);
  const auto noWinner = static_cast<std::int16_t>(minD - 1);

  MatchResult out{TestImage(w, h, PixelType::S16C1), TestImage(w, h, PixelType::S16C1), {}};
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      out.disparity.at<std::int16_t>(x, y) = invalid;
      out.winnerRight.at<std::int16_t>(x, y) = noWinner;
    }
  }

  std::vector<std::int32_t> rowCosts(static_cast<std::size_t>(w) * count);
  std::vector<int> topOf(static_cast<std::size_t>(w));  // minD - 1: not matched
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      topOf[x] = matchedTop(x, y, w, h, params);
      if (topOf[x] < minD) continue;
      const int top = topOf[x];  // this pixel's own range: the region's, or shorter in the band
      ++out.stats.regionPixels;
      std::int32_t* c = &rowCosts[static_cast<std::size_t>(x) * count];
      for (int d = minD; d <= top; ++d)
        c[d - minD] = sadCost(left, right, x, y, d, r);

      // Winner: least cost, first (smallest d) among equals.
      int best = minD;
      for (int d = minD; d <= top; ++d) {
        if (c[d - minD] < c[best - minD]) best = d;
      }
      for (int d = minD; d <= top; ++d) {
        if (d != best && c[d - minD] == c[best - minD]) {
          ++out.stats.tiedWinner;
          break;
        }
      }
      if (best == minD || best == top) ++out.stats.rangeEndWinner;

      if (params.textureThreshold > 0) {
        long sum = 0;
        for (int j = -r; j <= r; ++j)
          for (int i = -r; i <= r; ++i)
            sum += texture.row<std::uint8_t>(y + j)[x + i];
        if (sum < params.textureThreshold) {
          ++out.stats.textureRejected;
          continue;
        }
      }
      if (params.uniquenessRatio > 0) {
        const std::int64_t c0 = c[best - minD];
        const std::int64_t t = c0 + c0 * params.uniquenessRatio / 100;
        bool unique = true;
        for (int d = minD; d <= top; ++d) {
          if (std::abs(d - best) > 1 && c[d - minD] <= t) unique = false;
        }
        if (!unique) {
          ++out.stats.uniquenessRejected;
          continue;
        }
      }
      const std::int64_t c0 = c[best - minD];
      std::int64_t cm = 0, cp = 0;
      if (best == minD && best == top) {
        cm = cp = c0;  // a range of one: no neighbour, offset 0
      } else if (best == minD) {
        cp = c[best + 1 - minD];
        cm = cp;
      } else if (best == top) {
        cm = c[best - 1 - minD];
        cp = cm;
      } else {
        cm = c[best - 1 - minD];
        cp = c[best + 1 - minD];
      }
      const std::int64_t den = cm + cp - 2 * c0 + (cm > cp ? cm - cp : cp - cm);
      std::int64_t off = 0;
      if (den > 0) off = (cm - cp) * 256 / den;  // C++ division truncates toward 0
      if (off != 0) ++out.stats.subpixelNonZero;
      out.disparity.at<std::int16_t>(x, y) =
          static_cast<std::int16_t>(floorDiv(std::int64_t{best} * 256 + off + 8, 16));
      ++out.stats.valid;
    }

    // The right view's winner, from the same costs.
    for (int xr = 0; xr < w; ++xr) {
      bool found = false;
      std::int32_t bestCost = 0;
      int bestD = 0;
      for (int d = minD; d <= maxD; ++d) {
        const int x = xr + d;
        if (x < 0 || x >= w || d > topOf[x]) continue;
        const std::int32_t cost = rowCosts[static_cast<std::size_t>(x) * count + (d - minD)];
        if (!found || cost < bestCost) {
          found = true;
          bestCost = cost;
          bestD = d;
        }
      }
      if (found) {
        out.winnerRight.at<std::int16_t>(xr, y) = static_cast<std::int16_t>(bestD);
        ++out.stats.rightWinners;
      }
    }
  }
  return out;
}

TestImage leftRightCheck(const ConstImageView& disparity, const ConstImageView& winnerRight,
                         const StereoParams& params) {
  TestImage out = copyOf(disparity);
  if (params.disp12MaxDiff < 0) return out;
  const int w = disparity.width;
  const std::int16_t invalid = static_cast<std::int16_t>((params.minDisparity - 1) * 16);
  const int noWinner = params.minDisparity - 1;
  for (int y = 0; y < disparity.height; ++y) {
    for (int x = 0; x < w; ++x) {
      const int d = disparity.row<std::int16_t>(y)[x];
      if (d == invalid) continue;
      const auto dl = static_cast<int>(floorDiv(d + 8, 16));  // nearest px, halves up
      const int xr = x - dl;
      if (xr < 0 || xr >= w) continue;
      const int wr = winnerRight.row<std::int16_t>(y)[xr];
      if (wr == noWinner) continue;
      if (std::abs(dl - wr) > params.disp12MaxDiff) out.at<std::int16_t>(x, y) = invalid;
    }
  }
  return out;
}

TestImage filterSpeckles(const ConstImageView& disparity, const StereoParams& params) {
  TestImage out = copyOf(disparity);
  if (params.speckleWindowSize == 0) return out;
  const int w = disparity.width;
  const int h = disparity.height;
  const std::int16_t invalid = static_cast<std::int16_t>((params.minDisparity - 1) * 16);
  const auto value = [&](int x, int y) -> int { return disparity.row<std::int16_t>(y)[x]; };
  std::vector<int> label(static_cast<std::size_t>(w) * h, -1);
  std::vector<long> blobSize;
  for (int y0 = 0; y0 < h; ++y0) {
    for (int x0 = 0; x0 < w; ++x0) {
      if (value(x0, y0) == invalid || label[static_cast<std::size_t>(y0) * w + x0] >= 0) continue;
      const int id = static_cast<int>(blobSize.size());
      blobSize.push_back(0);
      std::deque<std::pair<int, int>> queue{{x0, y0}};
      label[static_cast<std::size_t>(y0) * w + x0] = id;
      while (!queue.empty()) {
        const auto [x, y] = queue.front();
        queue.pop_front();
        ++blobSize[id];
        const std::pair<int, int> neighbours[] = {{x - 1, y}, {x + 1, y}, {x, y - 1}, {x, y + 1}};
        for (const auto& [nx, ny] : neighbours) {
          if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
          if (value(nx, ny) == invalid) continue;
          if (std::abs(value(nx, ny) - value(x, y)) > params.speckleRange) continue;
          int& l = label[static_cast<std::size_t>(ny) * w + nx];
          if (l >= 0) continue;
          l = id;
          queue.emplace_back(nx, ny);
        }
      }
    }
  }
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const int l = label[static_cast<std::size_t>(y) * w + x];
      if (l >= 0 && blobSize[l] <= params.speckleWindowSize) out.at<std::int16_t>(x, y) = invalid;
    }
  }
  return out;
}

TestImage medianFilter(const ConstImageView& src, int kernelSize, int minValid,
                       std::int16_t invalid) {
  TestImage out(src.width, src.height, PixelType::S16C1);
  const int h = kernelSize / 2;
  for (int y = 0; y < src.height; ++y) {
    for (int x = 0; x < src.width; ++x) {
      std::vector<std::int16_t> values;
      for (int j = -h; j <= h; ++j) {
        for (int i = -h; i <= h; ++i) {
          const int xx = x + i, yy = y + j;
          if (xx < 0 || yy < 0 || xx >= src.width || yy >= src.height) continue;
          const std::int16_t v = src.row<std::int16_t>(yy)[xx];
          if (v != invalid) values.push_back(v);
        }
      }
      const bool centreValid = src.row<std::int16_t>(y)[x] != invalid;
      const int n = static_cast<int>(values.size());
      if (!centreValid && n < minValid) {
        out.at<std::int16_t>(x, y) = invalid;
        continue;
      }
      const auto rank = values.begin() + (n - 1) / 2;
      std::nth_element(values.begin(), rank, values.end());
      out.at<std::int16_t>(x, y) = *rank;
    }
  }
  return out;
}

void horopterMask(const ConstImageView& disparity, std::span<const std::int16_t> thresholds,
                  std::int16_t invalid, const ConstImageView& image, TestImage& mask,
                  TestImage& segmented) {
  mask = TestImage(disparity.width, disparity.height, PixelType::U8C1);
  if (!image.empty()) segmented = TestImage(image.width, image.height, image.type);
  const int channels = image.type == PixelType::U8C3 ? 3 : 1;
  for (int y = 0; y < disparity.height; ++y) {
    for (int x = 0; x < disparity.width; ++x) {
      const std::int16_t d = disparity.row<std::int16_t>(y)[x];
      const bool inside = d != invalid && d >= thresholds[x];
      mask.at<std::uint8_t>(x, y) = inside ? 255 : 0;
      if (image.empty()) continue;
      for (int c = 0; c < channels; ++c) {
        segmented.row<std::uint8_t>(y)[x * channels + c] =
            inside ? image.row<std::uint8_t>(y)[x * channels + c] : 0;
      }
    }
  }
}

}  // namespace horopter::test::naive
