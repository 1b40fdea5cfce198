// Known answers: scenes whose disparities follow from how they were built.
#include <cstdint>
#include <string>

#include <gtest/gtest.h>

#include "horopter/kernels/kernels.hpp"
#include "horopter/vision/frontend.hpp"
#include "naive_reference.hpp"
#include "sad/sad.hpp"
#include "test_support.hpp"

namespace horopter::test {
namespace {

struct ShiftCase {
  int minD, numD, shift, blockSize;
};

std::string describe(const ShiftCase& c) {
  return "range " + std::to_string(c.minD) + ".." + std::to_string(c.minD + c.numD - 1) +
         ", shift " + std::to_string(c.shift) + ", block " + std::to_string(c.blockSize);
}

const ShiftCase kShiftCases[] = {
    {0, 16, 0, 5},                                    // at the low end of the range
    {0, 16, 3, 5},   {0, 16, 7, 9},  {0, 16, 15, 9},  // at the high end of the range
    {-8, 16, -5, 5},                                  // negative disparity
    {-8, 16, 6, 9},  {4, 32, 10, 5}, {4, 32, 35, 9}, {-20, 16, -12, 7},
};

// A random-walk texture (every horizontal step +-kWalkStep) shifted by exactly
// k pixels: the cost is 0 at k and rises by the same amount at k - 1 and
// k + 1, so the sub-pixel offset is 0 and the disparity is exactly 16 k.
TEST(KnownAnswer, ExactShiftGivesExactDisparity) {
  for (const ShiftCase& c : kShiftCases) {
    SCOPED_TRACE(describe(c));
    StereoParams p;
    p.minDisparity = c.minD;
    p.numDisparities = c.numD;
    p.blockSize = c.blockSize;
    p.textureThreshold = 0;
    p.uniquenessRatio = 15;
    const int w = 100, h = 24;
    const StereoPair pair = shiftedPair(w, h, c.shift, Texture::RandomWalk, 77 + c.shift);
    TestImage d(w, h, PixelType::S16C1), wr(w, h, PixelType::S16C1);
    matchBlocks(pair.left.view(), pair.right.view(), {}, p, d.view(), wr.view());
    const MatchRegion region = matchRegion(w, h, p);
    ASSERT_FALSE(region.empty());
    long checked = 0;
    for (int y = region.y0; y < region.y1; ++y) {
      for (int x = region.x0; x < region.x1; ++x) {
        ASSERT_EQ(d.at<std::int16_t>(x, y), c.shift * 16) << "at (" << x << ", " << y << ")";
        ++checked;
      }
      // Every right pixel whose true partner lies in the region picks k too.
      for (int xr = 0; xr < w; ++xr) {
        if (xr + c.shift >= region.x0 && xr + c.shift < region.x1) {
          ASSERT_EQ(wr.at<std::int16_t>(xr, y), c.shift)
              << "right pixel (" << xr << ", " << y << ")";
        }
      }
    }
    EXPECT_GT(checked, 0);
  }
}

// Any texture shifted by k pixels: the whole-pixel disparity is k (the
// sub-pixel part may move by less than half a pixel).
TEST(KnownAnswer, ShiftedUniformTextureRoundsToShift) {
  for (const ShiftCase& c : kShiftCases) {
    SCOPED_TRACE(describe(c));
    StereoParams p;
    p.minDisparity = c.minD;
    p.numDisparities = c.numD;
    p.blockSize = c.blockSize;
    p.textureThreshold = 0;
    const int w = 100, h = 20;
    const StereoPair pair = shiftedPair(w, h, c.shift, Texture::Uniform, 5 + c.shift);
    TestImage d(w, h, PixelType::S16C1), wr(w, h, PixelType::S16C1);
    matchBlocks(pair.left.view(), pair.right.view(), {}, p, d.view(), wr.view());
    const MatchRegion region = matchRegion(w, h, p);
    for (int y = region.y0; y < region.y1; ++y) {
      for (int x = region.x0; x < region.x1; ++x) {
        const int v = d.at<std::int16_t>(x, y);
        ASSERT_NE(v, invalidDisparity(p)) << "at (" << x << ", " << y << ")";
        ASSERT_GE(v, c.shift * 16 - 8) << "at (" << x << ", " << y << ")";
        ASSERT_LT(v, c.shift * 16 + 8) << "at (" << x << ", " << y << ")";
      }
    }
  }
}

// A fronto-parallel plane through the whole front end (matching, left-right
// check, speckles, median): unfiltered matching of the random-walk texture
// keeps the disparity exact, and cleanup must not disturb a constant map.
TEST(KnownAnswer, FrontoParallelPlaneThroughFrontendIsExact) {
  for (int k : {2, 6, 11}) {
    StereoParams p;
    p.numDisparities = 16;
    p.blockSize = 7;
    p.preFilterType = PreFilterType::None;
    p.textureThreshold = 0;
    const int w = 96, h = 40;
    const StereoPair pair = shiftedPair(w, h, k, Texture::RandomWalk, 1234 + k);
    StereoFrontend frontend(p, MedianParams{});
    const Image& out = frontend.computeDisparity(pair.left.view(), pair.right.view());
    const MatchRegion region = matchRegion(w, h, p);
    long valid = 0;
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const std::int16_t v = out.row<std::int16_t>(y)[x];
        const bool inRegion = x >= region.x0 && x < region.x1 && y >= region.y0 && y < region.y1;
        if (inRegion) {
          ASSERT_EQ(v, 16 * k) << "k " << k << " at (" << x << ", " << y << ")";
        }
        // The median may fill holes just outside the region, with the plane's value.
        if (v != invalidDisparity(p)) {
          ASSERT_EQ(v, 16 * k) << "k " << k << " at (" << x << ", " << y << ")";
          ++valid;
        }
      }
    }
    EXPECT_GE(valid, static_cast<long>(region.x1 - region.x0) * (region.y1 - region.y0));
  }
}

// The same plane with the default settings (x-Sobel prefilter, texture and
// uniqueness checks): every pixel of the region is valid and rounds to k.
TEST(KnownAnswer, FrontoParallelPlaneWithDefaultSettings) {
  for (int k : {3, 9}) {
    StereoParams p;
    p.numDisparities = 16;
    const int w = 120, h = 48;
    const StereoPair pair = shiftedPair(w, h, k, Texture::Uniform, 99 + k);
    StereoFrontend frontend(p, MedianParams{});
    const Image& out = frontend.computeDisparity(pair.left.view(), pair.right.view());
    const MatchRegion region = matchRegion(w, h, p);
    for (int y = region.y0; y < region.y1; ++y) {
      for (int x = region.x0; x < region.x1; ++x) {
        const int v = out.row<std::int16_t>(y)[x];
        ASSERT_GE(v, 16 * k - 8) << "k " << k << " at (" << x << ", " << y << ")";
        ASSERT_LT(v, 16 * k + 8) << "k " << k << " at (" << x << ", " << y << ")";
      }
    }
  }
}

// A near square in front of a far background. The background just left of the
// square is hidden from the right camera: the left-right check must mark that
// strip invalid, while without the check the matcher gives it (wrong) values.
TEST(KnownAnswer, LeftRightCheckInvalidatesOccludedStrip) {
  const StepScene scene{60, 100, 10, 40, 14, 4};
  const int w = 120, h = 50;
  const int stripX0 = scene.x0 - (scene.nearD - scene.farD), stripX1 = scene.x0;
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const StereoPair pair = stepScenePair(w, h, scene, seed);
    StereoParams p;
    p.numDisparities = 16;
    p.blockSize = 5;
    p.textureThreshold = 0;
    p.uniquenessRatio = 0;
    const int r = p.blockSize / 2;
    TestImage raw(w, h, PixelType::S16C1), wr(w, h, PixelType::S16C1);
    matchBlocks(pair.left.view(), pair.right.view(), {}, p, raw.view(), wr.view());

    TestImage checked = raw.clone();
    leftRightCheck(checked.view(), wr.view(), p);
    TestImage unchecked = raw.clone();
    StereoParams off = p;
    off.disp12MaxDiff = -1;
    leftRightCheck(unchecked.view(), wr.view(), off);
    EXPECT_TRUE(sameImage(raw.view(), unchecked.view())) << "disp12MaxDiff < 0 must be a no-op";

    const std::int16_t inv = invalidDisparity(p);
    long strip = 0, stripInvalid = 0, stripValidUnchecked = 0, core = 0, coreInvalid = 0;
    for (int y = scene.y0 + r; y < scene.y1 - r; ++y) {
      for (int x = stripX0; x < stripX1; ++x) {
        ++strip;
        stripInvalid += checked.at<std::int16_t>(x, y) == inv;
        if (x >= stripX0 + r && x < stripX1 - r) {
          ++core;
          coreInvalid += checked.at<std::int16_t>(x, y) == inv;
        }
        stripValidUnchecked += unchecked.at<std::int16_t>(x, y) != inv;
      }
    }
    SCOPED_TRACE("seed " + std::to_string(seed));
    // Windows that straddle the strip's edges may match either surface, so
    // the edges of the invalid band can move by a column; its core cannot.
    EXPECT_EQ(coreInvalid, core) << "occluded pixels left valid by the check";
    EXPECT_GE(stripInvalid * 10, strip * 9) << stripInvalid << " of " << strip << " invalid";
    EXPECT_EQ(stripValidUnchecked, strip) << "without the check every region pixel is valid";

    // Visible surfaces away from the edges keep their disparities.
    for (int y = scene.y0 + r; y < scene.y1 - r; ++y) {
      for (int x = scene.x0 + r; x < scene.x1 - r; ++x)
        ASSERT_EQ((checked.at<std::int16_t>(x, y) + 8) >> 4, scene.nearD) << x << "," << y;
    }
    for (int y = r; y < h - r; ++y) {
      for (int x = matchRegion(w, h, p).x0; x < stripX0 - r; ++x)
        ASSERT_EQ((checked.at<std::int16_t>(x, y) + 8) >> 4, scene.farD) << x << "," << y;
    }
  }
}

// A flat pair: every cost is 0, so every disparity ties. The smallest wins
// (minDisparity, with no sub-pixel offset), unless uniqueness or texture
// rejects the pixel.
TEST(KnownAnswer, FlatImagesTieToSmallestDisparity) {
  for (int minD : {0, -8, 4}) {
    StereoParams p;
    p.minDisparity = minD;
    p.numDisparities = 16;
    p.blockSize = 5;
    p.textureThreshold = 0;
    p.uniquenessRatio = 0;
    const int w = 48, h = 11;
    TestImage left(w, h, PixelType::U8C1), right(w, h, PixelType::U8C1);
    left.fillBytes(77);
    right.fillBytes(77);
    TestImage d(w, h, PixelType::S16C1), wr(w, h, PixelType::S16C1);
    matchBlocks(left.view(), right.view(), {}, p, d.view(), wr.view());
    const MatchRegion region = matchRegion(w, h, p);
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const bool inRegion = x >= region.x0 && x < region.x1 && y >= region.y0 && y < region.y1;
        ASSERT_EQ(d.at<std::int16_t>(x, y), inRegion ? minD * 16 : invalidDisparity(p))
            << "minD " << minD << " at (" << x << ", " << y << ")";
        // The right winner: the smallest d whose left pixel is in the region.
        int want = minD - 1;
        if (y >= region.y0 && y < region.y1) {
          for (int dd = minD; dd < minD + 16; ++dd) {
            if (x + dd >= region.x0 && x + dd < region.x1) {
              want = dd;
              break;
            }
          }
        }
        ASSERT_EQ(wr.at<std::int16_t>(x, y), want)
            << "minD " << minD << " right (" << x << ", " << y << ")";
      }
    }

    // Uniqueness: every other disparity has the winner's cost -> all invalid.
    StereoParams unique = p;
    unique.uniquenessRatio = 15;
    matchBlocks(left.view(), right.view(), {}, unique, d.view(), wr.view());
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        ASSERT_EQ(d.at<std::int16_t>(x, y), invalidDisparity(p));

    // Texture: a flat image has none -> all invalid.
    StereoParams textured = p;
    textured.textureThreshold = 1;
    TestImage texture(w, h, PixelType::U8C1);
    prefilterXSobel(left.view(), p.preFilterCap, {}, texture.view());
    matchBlocks(left.view(), right.view(), texture.view(), textured, d.view(), wr.view());
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        ASSERT_EQ(d.at<std::int16_t>(x, y), invalidDisparity(p));
  }
}

// Vertical stripes 0/255 of period 2 shifted by 7: the cost is 0 at every odd
// disparity and maximal at every even one. The smallest zero (1) wins; its
// neighbours cost the same, so the offset is 0. With uniqueness on, the
// repeated minima make every pixel invalid.
TEST(KnownAnswer, PeriodicStripesPickSmallestOfEqualMinima) {
  StereoParams p;
  p.numDisparities = 16;
  p.blockSize = 5;
  p.textureThreshold = 0;
  p.uniquenessRatio = 0;
  const int w = 64, h = 9;
  TestImage left(w, h, PixelType::U8C1), right(w, h, PixelType::U8C1);
  const auto stripe = [](int x) -> std::uint8_t { return x % 2 ? 255 : 0; };
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      left.at<std::uint8_t>(x, y) = stripe(x);
      right.at<std::uint8_t>(x, y) = stripe(x + 7);
    }
  }
  TestImage d(w, h, PixelType::S16C1), wr(w, h, PixelType::S16C1);
  matchBlocks(left.view(), right.view(), {}, p, d.view(), wr.view());
  const MatchRegion region = matchRegion(w, h, p);
  for (int y = region.y0; y < region.y1; ++y)
    for (int x = region.x0; x < region.x1; ++x)
      ASSERT_EQ(d.at<std::int16_t>(x, y), 1 * 16) << x << "," << y;
  p.uniquenessRatio = 15;
  matchBlocks(left.view(), right.view(), {}, p, d.view(), wr.view());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      ASSERT_EQ(d.at<std::int16_t>(x, y), invalidDisparity(p)) << x << "," << y;
}

// The narrowest accepted image has a one-column region, and it is matched.
TEST(KnownAnswer, NarrowestImageHasOneColumnRegion) {
  for (int minD : {-8, 0, 4}) {
    StereoParams p;
    p.minDisparity = minD;
    p.numDisparities = 16;
    p.blockSize = 5;
    p.textureThreshold = 0;
    // Columns needed: the block plus the span of the disparities and zero.
    const int maxD = minD + 15;
    const int w = p.blockSize + std::max(maxD, 0) - std::min(minD, 0);
    const int h = 7;
    const MatchRegion region = matchRegion(w, h, p);
    ASSERT_EQ(region.x1 - region.x0, 1) << "minD " << minD << ", width " << w;
    EXPECT_TRUE(matchRegion(w - 1, h, p).empty()) << "minD " << minD << ", width " << w - 1;
    const int k = minD + 5;
    const StereoPair pair = shiftedPair(w, h, k, Texture::RandomWalk, 3);
    TestImage d(w, h, PixelType::S16C1), wr(w, h, PixelType::S16C1);
    matchBlocks(pair.left.view(), pair.right.view(), {}, p, d.view(), wr.view());
    for (int y = region.y0; y < region.y1; ++y)
      EXPECT_EQ(d.at<std::int16_t>(region.x0, y), 16 * k) << "minD " << minD;
  }
}

}  // namespace
}  // namespace horopter::test
