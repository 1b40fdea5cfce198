// The scalar reference kernels against brute force written from their
// Semantics blocks (tests/support/naive_reference.cpp), exactly, on small
// random inputs over several seeds, sizes and parameters.
#include <cstdint>
#include <limits>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "horopter/kernels/kernels.hpp"
#include "naive_reference.hpp"
#include "sad/sad.hpp"
#include "test_support.hpp"

namespace horopter::test {
namespace {

std::string describe(const StereoParams& p) {
  return "minDisparity " + std::to_string(p.minDisparity) + ", numDisparities " +
         std::to_string(p.numDisparities) + ", blockSize " + std::to_string(p.blockSize) +
         ", textureThreshold " + std::to_string(p.textureThreshold) + ", uniquenessRatio " +
         std::to_string(p.uniquenessRatio) + ", disp12MaxDiff " + std::to_string(p.disp12MaxDiff) +
         ", speckleWindowSize " + std::to_string(p.speckleWindowSize) + ", speckleRange " +
         std::to_string(p.speckleRange) + ", leftBand " + std::to_string(p.leftBand);
}

// ---------------------------------------------------------------------------
// x-Sobel prefilter

TEST(BruteForcePrefilter, MatchesNaiveSobelWithReflect101Borders) {
  const int widths[] = {1, 2, 3, 4, 5, 31, 33, 65};
  const int heights[] = {1, 2, 3, 4, 7};
  const int caps[] = {1, 7, 31, 63};
  int seed = 0;
  for (int w : widths) {
    for (int h : heights) {
      for (int cap : caps) {
        for (int saturated = 0; saturated < 2; ++saturated) {
          ++seed;
          SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h) + ", cap " +
                       std::to_string(cap) + (saturated ? ", 0/255 only" : ", uniform"));
          TestImage src = randomImage(w, h, PixelType::U8C1, 1000 + seed, 0, 255);
          if (saturated) {
            for (int y = 0; y < h; ++y)
              for (int x = 0; x < w; ++x)
                src.at<std::uint8_t>(x, y) = src.at<std::uint8_t>(x, y) < 128 ? 0 : 255;
          }
          TestImage wantFiltered, wantTexture;
          naive::prefilterXSobel(src.view(), cap, wantFiltered, wantTexture);
          TestImage filtered(w, h, PixelType::U8C1), texture(w, h, PixelType::U8C1);
          prefilterXSobel(src.view(), cap, filtered.view(), texture.view());
          EXPECT_TRUE(sameImage(wantFiltered.view(), filtered.view()));
          EXPECT_TRUE(sameImage(wantTexture.view(), texture.view()));
          // Either output alone gives the same values.
          TestImage onlyFiltered(w, h, PixelType::U8C1), onlyTexture(w, h, PixelType::U8C1);
          prefilterXSobel(src.view(), cap, onlyFiltered.view(), {});
          prefilterXSobel(src.view(), cap, {}, onlyTexture.view());
          EXPECT_TRUE(sameImage(wantFiltered.view(), onlyFiltered.view()));
          EXPECT_TRUE(sameImage(wantTexture.view(), onlyTexture.view()));
        }
      }
    }
  }
}

TEST(BruteForcePrefilter, ReachesBothClipLimitsAndZero) {
  // A 0/255 checkerboard of columns saturates the response; flat areas give 0.
  const int cap = 31;
  TestImage src(12, 5, PixelType::U8C1);
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 12; ++x)
      src.at<std::uint8_t>(x, y) = x < 6 ? ((x / 2) % 2 ? 255 : 0) : 100;
  TestImage filtered(12, 5, PixelType::U8C1), texture(12, 5, PixelType::U8C1);
  prefilterXSobel(src.view(), cap, filtered.view(), texture.view());
  bool low = false, high = false, flat = false;
  for (int y = 0; y < 5; ++y) {
    for (int x = 0; x < 12; ++x) {
      const int f = filtered.at<std::uint8_t>(x, y);
      low |= f == 0;
      high |= f == 2 * cap;
      flat |= f == cap;
      EXPECT_EQ(texture.at<std::uint8_t>(x, y), f > cap ? f - cap : cap - f);
    }
    EXPECT_EQ(filtered.at<std::uint8_t>(0, y), cap) << "column 0 has no left neighbour";
    EXPECT_EQ(filtered.at<std::uint8_t>(11, y), cap) << "the last column has no right neighbour";
  }
  EXPECT_TRUE(low);
  EXPECT_TRUE(high);
  EXPECT_TRUE(flat);
}

// ---------------------------------------------------------------------------
// SAD block matching

// The closed-form region of sad.hpp against the spec's definition, pixel by pixel.
TEST(BruteForceMatch, MatchRegionIsWhereEveryWindowFits) {
  for (int blockSize : {3, 5, 9, 21}) {
    for (int minD : {-40, -20, -8, -1, 0, 1, 4, 17}) {
      for (int numD : {16, 32}) {
        for (int w : {1, 10, 31, 33, 65, 100}) {
          for (int h : {1, 3, 9, 12, 30}) {
            StereoParams p;
            p.blockSize = blockSize;
            p.minDisparity = minD;
            p.numDisparities = numD;
            const MatchRegion region = matchRegion(w, h, p);
            bool any = false;
            for (int y = 0; y < h; ++y) {
              for (int x = 0; x < w; ++x) {
                const bool inside =
                    x >= region.x0 && x < region.x1 && y >= region.y0 && y < region.y1;
                const bool want = naive::inMatchRegion(x, y, w, h, p);
                any |= want;
                ASSERT_EQ(inside, want) << "pixel (" << x << ", " << y << ") of " << w << "x" << h
                                        << ", " << describe(p);
              }
            }
            EXPECT_EQ(region.empty(), !any) << w << "x" << h << ", " << describe(p);
          }
        }
      }
    }
  }
}

// Inputs that exercise every branch: a noisy shifted texture (unique winners,
// sub-pixel offsets), a low-entropy one and sparse dots on flat grey (ties),
// an unrelated pair (uniqueness failures), and a sparse texture map (the
// texture check fails about half the time at the threshold blockSize^2).
struct MatchCase {
  TestImage left, right, texture;
  std::string what;
};

MatchCase makeMatchCase(int w, int h, const StereoParams& p, std::uint64_t seed, int kind) {
  const int shift = p.minDisparity + static_cast<int>(seed % p.numDisparities);
  MatchCase c;
  switch (kind) {
    case 0: {
      StereoPair pair = shiftedPair(w, h, shift, Texture::Uniform, seed, 12);
      c = {std::move(pair.left), std::move(pair.right), {}, "noisy shifted uniform texture"};
      break;
    }
    case 1: {
      StereoPair pair = shiftedPair(w, h, shift, Texture::LowEntropy, seed, 0);
      c = {std::move(pair.left), std::move(pair.right), {}, "shifted low-entropy texture"};
      // Break part of the match so that some costs stay above zero.
      Rng rng(seed);
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
          if (rng.chance(10))
            c.right.at<std::uint8_t>(x, y) = static_cast<std::uint8_t>(rng.uniform(0, 3));
      break;
    }
    case 2: {
      // Sparse dots on a flat grey: most windows see the same few dots at
      // many disparities, so equal costs (ties) are common.
      c = {TestImage(w, h, PixelType::U8C1),
           TestImage(w, h, PixelType::U8C1),
           {},
           "sparse dots on flat grey"};
      Rng rng(seed);
      for (TestImage* img : {&c.left, &c.right})
        for (int y = 0; y < h; ++y)
          for (int x = 0; x < w; ++x)
            img->at<std::uint8_t>(x, y) =
                static_cast<std::uint8_t>(rng.chance(4) ? rng.uniform(0, 255) : 128);
      break;
    }
    default:
      c = {randomImage(w, h, PixelType::U8C1, seed, 0, 255),
           randomImage(w, h, PixelType::U8C1, seed + 7, 0, 255),
           {},
           "unrelated uniform images"};
      break;
  }
  c.texture = randomImage(w, h, PixelType::U8C1, seed + 13, 0, 2);
  c.what += " (seed " + std::to_string(seed) + ", shift " + std::to_string(shift) + ")";
  return c;
}

std::string matchParamName(const ::testing::TestParamInfo<std::tuple<int, int, int>>& p) {
  const int minD = std::get<1>(p.param);
  std::ostringstream name;
  name << "block" << std::get<0>(p.param) << "_min" << (minD < 0 ? "M" : "") << std::abs(minD)
       << "_num" << std::get<2>(p.param);
  return name.str();
}

class BruteForceMatch : public ::testing::TestWithParam<std::tuple<int, int, int>> {};

TEST_P(BruteForceMatch, EqualsNaiveQuadrupleLoop) {
  const auto [blockSize, minD, numD] = GetParam();
  naive::MatchStats total;
  long casesRun = 0;
  for (int w : {31, 33, 65}) {
    for (int extraRows : {0, 1, 5}) {
      const int h = blockSize + extraRows;
      for (std::uint64_t seed = 1; seed <= 5; ++seed) {
        for (int kind = 0; kind < 4; ++kind) {
          for (int texture : {0, 1}) {
            for (int uniqueness : {0, 1}) {
              StereoParams p;
              p.blockSize = blockSize;
              p.minDisparity = minD;
              p.numDisparities = numD;
              p.textureThreshold = texture ? blockSize * blockSize : 0;
              p.uniquenessRatio = uniqueness ? 15 : 0;
              if (matchRegion(w, h, p).empty()) continue;  // rejected input, see bad_input_test
              const MatchCase c = makeMatchCase(w, h, p, seed * 131 + kind * 7 + w, kind);
              SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h) + ", " + c.what + ", " +
                           describe(p));
              const naive::MatchResult want =
                  naive::matchBlocks(c.left.view(), c.right.view(), c.texture.view(), p);
              TestImage disparity(w, h, PixelType::S16C1), winner(w, h, PixelType::S16C1);
              disparity.fillBytes(0x5A);
              winner.fillBytes(0x5A);
              matchBlocks(c.left.view(), c.right.view(), c.texture.view(), p, disparity.view(),
                          winner.view());
              ASSERT_TRUE(sameImage(want.disparity.view(), disparity.view())) << "disparity";
              ASSERT_TRUE(sameImage(want.winnerRight.view(), winner.view())) << "winnerRight";
              ++casesRun;
              total.regionPixels += want.stats.regionPixels;
              total.valid += want.stats.valid;
              total.textureRejected += want.stats.textureRejected;
              total.uniquenessRejected += want.stats.uniquenessRejected;
              total.subpixelNonZero += want.stats.subpixelNonZero;
              total.tiedWinner += want.stats.tiedWinner;
              total.rangeEndWinner += want.stats.rangeEndWinner;
              total.rightWinners += want.stats.rightWinners;
            }
          }
        }
      }
    }
  }
  // The inputs must have exercised every rule of the spec.
  ASSERT_GT(casesRun, 0);
  EXPECT_GT(total.valid, 0);
  EXPECT_GT(total.textureRejected, 0);
  EXPECT_GT(total.uniquenessRejected, 0);
  EXPECT_GT(total.subpixelNonZero, 0);
  EXPECT_GT(total.tiedWinner, 0);
  EXPECT_GT(total.rangeEndWinner, 0);
  EXPECT_GT(total.rightWinners, 0);
}

INSTANTIATE_TEST_SUITE_P(Params, BruteForceMatch,
                         ::testing::Combine(::testing::Values(3, 5, 9),
                                            ::testing::Values(0, -8, 4, -20),
                                            ::testing::Values(16, 32)),
                         matchParamName);

// The left band (StereoParams::leftBand): the columns left of the region,
// each matched over the disparities that fit there, against the naive
// loop's own reading of "fit"; band widths from one disparity to the whole
// range, the smallest widths the region allows and wider ones.
TEST(BruteForceMatch, LeftBandEqualsNaiveQuadrupleLoop) {
  long bandPixels = 0, bandValid = 0, casesRun = 0;
  for (int blockSize : {3, 9}) {
    for (int minD : {0, -8, 4}) {
      for (int numD : {16, 32}) {
        for (int band : {1, 2, 3, 16, numD}) {
          const int needed = blockSize + std::max(minD + numD - 1, 0) - std::min(minD, 0);
          for (int w : {needed, needed + 1, needed + 23}) {
            for (std::uint64_t seed = 1; seed <= 2; ++seed) {
              StereoParams p;
              p.blockSize = blockSize;
              p.minDisparity = minD;
              p.numDisparities = numD;
              p.leftBand = band;
              p.textureThreshold = seed == 1 ? 0 : blockSize * blockSize;
              p.uniquenessRatio = seed == 1 ? 15 : 0;
              const int h = blockSize + 3;
              const int kind = static_cast<int>(seed + w) % 4;
              const MatchCase c = makeMatchCase(w, h, p, seed * 977 + w + band, kind);
              SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h) + ", " + c.what + ", " +
                           describe(p));
              const naive::MatchResult want =
                  naive::matchBlocks(c.left.view(), c.right.view(), c.texture.view(), p);
              TestImage disparity(w, h, PixelType::S16C1), winner(w, h, PixelType::S16C1);
              disparity.fillBytes(0x5A);
              winner.fillBytes(0x5A);
              matchBlocks(c.left.view(), c.right.view(), c.texture.view(), p, disparity.view(),
                          winner.view());
              ASSERT_TRUE(sameImage(want.disparity.view(), disparity.view())) << "disparity";
              ASSERT_TRUE(sameImage(want.winnerRight.view(), winner.view())) << "winnerRight";
              ++casesRun;
              const MatchRegion region = matchRegion(w, h, p);
              bandPixels += static_cast<long>(region.x0 - region.bandX0) * (region.y1 - region.y0);
              for (int y = region.y0; y < region.y1; ++y)
                for (int x = region.bandX0; x < region.x0; ++x)
                  bandValid += disparity.at<std::int16_t>(x, y) != invalidDisparity(p);
            }
          }
        }
      }
    }
  }
  ASSERT_GT(casesRun, 0);
  EXPECT_GT(bandPixels, 0);
  EXPECT_GT(bandValid, 0) << "no band pixel was ever valid: the band went untested";
}

// Random configurations over the whole parameter space (kept small enough
// for brute force: at most about 4 million pixel differences each).
TEST(BruteForceMatch, RandomConfigurations) {
  Rng rng(2024);
  int run = 0;
  while (run < 60) {
    StereoParams p;
    p.blockSize = 2 * rng.uniform(1, 12) + 1;
    p.numDisparities = 16 * rng.uniform(1, 4);
    p.minDisparity = rng.uniform(-70, 40);
    const int textureMax = rng.uniform(1, 255);
    // Around the mean window sum of the texture image, so that both outcomes occur.
    p.textureThreshold =
        rng.chance(40) ? 0 : rng.uniform(1, p.blockSize * p.blockSize * textureMax);
    p.uniquenessRatio = rng.chance(30) ? 0 : rng.uniform(1, 1000);
    p.leftBand = rng.chance(50) ? 0 : rng.uniform(1, p.numDisparities);
    const int needed = p.blockSize + std::max(p.minDisparity + p.numDisparities - 1, 0) -
                       std::min(p.minDisparity, 0);
    const int w = needed + rng.uniform(0, 30);
    const int h = p.blockSize + rng.uniform(0, 6);
    const MatchRegion region = matchRegion(w, h, p);
    const long work = static_cast<long>(region.x1 - region.x0) * (region.y1 - region.y0) *
                      p.numDisparities * p.blockSize * p.blockSize;
    if (work > 4'000'000) continue;
    ++run;
    const std::uint64_t seed = rng.next();
    const MatchCase c = makeMatchCase(w, h, p, seed, static_cast<int>(seed % 4));
    TestImage texture = randomImage(w, h, PixelType::U8C1, seed + 1, 0, textureMax);
    SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h) + ", " + c.what + ", " + describe(p));
    const naive::MatchResult want =
        naive::matchBlocks(c.left.view(), c.right.view(), texture.view(), p);
    TestImage disparity(w, h, PixelType::S16C1), winner(w, h, PixelType::S16C1);
    matchBlocks(c.left.view(), c.right.view(), texture.view(), p, disparity.view(), winner.view());
    ASSERT_TRUE(sameImage(want.disparity.view(), disparity.view())) << "disparity";
    ASSERT_TRUE(sameImage(want.winnerRight.view(), winner.view())) << "winnerRight";
  }
}

// Prefiltered inputs, as the front end feeds them, with the default texture
// and uniqueness settings.
TEST(BruteForceMatch, PrefilteredInputsWithDefaultChecks) {
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    StereoParams p;
    p.numDisparities = 16;
    p.blockSize = 7;
    const StereoPair pair =
        shiftedPair(48, 14, static_cast<int>(seed * 3), Texture::Uniform, seed, 20);
    TestImage lf(48, 14, PixelType::U8C1), rf(48, 14, PixelType::U8C1),
        tex(48, 14, PixelType::U8C1);
    prefilterXSobel(pair.left.view(), p.preFilterCap, lf.view(), tex.view());
    prefilterXSobel(pair.right.view(), p.preFilterCap, rf.view(), {});
    const naive::MatchResult want = naive::matchBlocks(lf.view(), rf.view(), tex.view(), p);
    TestImage disparity(48, 14, PixelType::S16C1), winner(48, 14, PixelType::S16C1);
    matchBlocks(lf.view(), rf.view(), tex.view(), p, disparity.view(), winner.view());
    EXPECT_TRUE(sameImage(want.disparity.view(), disparity.view())) << "seed " << seed;
    EXPECT_TRUE(sameImage(want.winnerRight.view(), winner.view())) << "seed " << seed;
    EXPECT_GT(want.stats.valid, 0);
  }
}

// The guard below the range (sad_scalar.cpp's rules) from the naive matcher
// over the range and naive window costs: a valid left pixel is dropped when
// some counted checked disparity costs <= its uniqueness limit (its cost
// when the ratio is 0); a right pixel with a winner takes the smallest
// checked disparity of least cost when that is <= the range's least,
// written as min(g, minDisparity - 2).
TEST(BruteForceMatch, GuardBelowTheRangeFollowsItsRules) {
  long dropped = 0, retargeted = 0;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const int w = 61, h = 13;
    StereoParams p;
    p.minDisparity = 10 + static_cast<int>(seed % 3);
    p.numDisparities = 16;
    p.blockSize = 5;
    p.uniquenessRatio = seed % 2 == 0 ? 0 : 15;
    p.textureThreshold = 0;
    const BelowRangeGuard guard{1 + static_cast<int>(seed % 3), static_cast<int>(seed % 2) - 3};
    const StereoPair pair =
        shiftedPair(w, h, 4 + static_cast<int>(seed), Texture::Uniform, seed, 20);
    TestImage lf(w, h, PixelType::U8C1), rf(w, h, PixelType::U8C1);
    prefilterXSobel(pair.left.view(), p.preFilterCap, lf.view(), {});
    prefilterXSobel(pair.right.view(), p.preFilterCap, rf.view(), {});
    const naive::MatchResult plain = naive::matchBlocks(lf.view(), rf.view(), {}, p);
    TestImage disparity(w, h, PixelType::S16C1), winner(w, h, PixelType::S16C1);
    matchBlocks(lf.view(), rf.view(), {}, p, guard, disparity.view(), winner.view());

    const int r = p.blockSize / 2, minD = p.minDisparity, maxD = minD + p.numDisparities - 1;
    const MatchRegion region = matchRegion(w, h, p);
    std::vector<int> checked;
    for (int g = minD - guard.step; g >= guard.lowest; g -= guard.step)
      checked.push_back(g);
    const auto counts = [&](int x, int g) { return x - g + r <= w - 1; };
    TestImage want = plain.disparity.clone(), wantWinner = plain.winnerRight.clone();
    for (int y = region.y0; y < region.y1; ++y) {
      for (int x = region.x0; x < region.x1; ++x) {
        std::int16_t& d = want.view().row<std::int16_t>(y)[x];
        if (d == invalidDisparity(p)) continue;
        int b = minD;
        for (int k = minD + 1; k <= maxD; ++k)
          if (naive::sadCost(lf.view(), rf.view(), x, y, k, r) <
              naive::sadCost(lf.view(), rf.view(), x, y, b, r))
            b = k;
        const std::int64_t c0 = naive::sadCost(lf.view(), rf.view(), x, y, b, r);
        const std::int64_t limit = c0 + c0 * p.uniquenessRatio / 100;
        for (int g : checked)
          if (counts(x, g) && naive::sadCost(lf.view(), rf.view(), x, y, g, r) <= limit) {
            d = invalidDisparity(p);
            ++dropped;
            break;
          }
      }
      for (int xr = region.x0 - maxD; xr < region.x1 - minD; ++xr) {
        std::int16_t& wr = wantWinner.view().row<std::int16_t>(y)[xr];
        const std::int32_t rangeLeast = naive::sadCost(lf.view(), rf.view(), xr + wr, y, wr, r);
        std::int32_t least = std::numeric_limits<std::int32_t>::max();
        int leastG = 0;
        for (auto g = checked.rbegin(); g != checked.rend(); ++g) {  // increasing g
          if (xr + *g < region.x0 || !counts(xr + *g, *g)) continue;
          const std::int32_t c = naive::sadCost(lf.view(), rf.view(), xr + *g, y, *g, r);
          if (c < least) {
            least = c;
            leastG = *g;
          }
        }
        if (least <= rangeLeast) {
          wr = static_cast<std::int16_t>(std::min(leastG, minD - 2));
          ++retargeted;
        }
      }
    }
    EXPECT_TRUE(sameImage(want.view(), disparity.view())) << "seed " << seed;
    EXPECT_TRUE(sameImage(wantWinner.view(), winner.view())) << "seed " << seed;
  }
  EXPECT_GT(dropped, 0) << "no pixel dropped: the scenes test nothing";
  EXPECT_GT(retargeted, 0) << "no right winner moved below the range: the scenes test nothing";
}

// The largest costs (255 per pixel over a 255x255 window stay exact in int32)
// on a tall narrow strip, so the test stays small.
TEST(BruteForceMatch, LargestBlockSaturatedCostsStayExact) {
  const int w = 255 + 15 + 2, h = 256;
  TestImage left(w, h, PixelType::U8C1), right(w, h, PixelType::U8C1);
  TestImage texture(w, h, PixelType::U8C1);
  texture.fillBytes(255);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      left.at<std::uint8_t>(x, y) = 255;
      right.at<std::uint8_t>(x, y) = (x + y) % 3 == 0 ? 0 : 255;
    }
  // The texture sum of a 255x255 window of 255s is 16581375: the check passes
  // at that threshold and fails one above it. Uniqueness up to 1000 %.
  const int full = 255 * 255 * 255;
  const std::pair<int, int> checks[] = {{0, 0}, {full, 1000}, {full + 1, 1}, {full, 37}};
  for (const auto& [textureThreshold, uniqueness] : checks) {
    StereoParams p;
    p.blockSize = 255;
    p.numDisparities = 16;
    p.textureThreshold = textureThreshold;
    p.uniquenessRatio = uniqueness;
    SCOPED_TRACE(describe(p));
    // Only a 3x2 region: brute force stays cheap enough.
    const naive::MatchResult want =
        naive::matchBlocks(left.view(), right.view(), texture.view(), p);
    TestImage disparity(w, h, PixelType::S16C1), winner(w, h, PixelType::S16C1);
    matchBlocks(left.view(), right.view(), texture.view(), p, disparity.view(), winner.view());
    EXPECT_EQ(want.stats.regionPixels, 3 * 2);
    EXPECT_TRUE(sameImage(want.disparity.view(), disparity.view()));
    EXPECT_TRUE(sameImage(want.winnerRight.view(), winner.view()));
    if (textureThreshold > full) {
      EXPECT_EQ(want.stats.textureRejected, 6);
    }
  }
}

// ---------------------------------------------------------------------------
// Left-right check

TEST(BruteForceLeftRight, MatchesFormulaOnRandomMaps) {
  for (int minD : {0, -8, 4}) {
    for (int maxDiff : {-1, 0, 1, 2, 5}) {
      for (std::uint64_t seed = 1; seed <= 4; ++seed) {
        StereoParams p;
        p.minDisparity = minD;
        p.numDisparities = 16;
        p.disp12MaxDiff = maxDiff;
        const int w = 37, h = 9;
        // Any value of the range, so that the rounding of halves is exercised.
        TestImage d = randomDisparityMap(w, h, p, seed, 15);
        Rng rng(seed + 99);
        for (int y = 0; y < h; ++y)
          for (int x = 0; x < w; ++x)
            if (rng.chance(30))
              d.at<std::int16_t>(x, y) =
                  static_cast<std::int16_t>(rng.uniform(minD * 16, (minD + 15) * 16 + 8));
        TestImage wr = randomImage(w, h, PixelType::S16C1, seed + 5, minD - 1, minD + 15);
        SCOPED_TRACE(describe(p) + ", seed " + std::to_string(seed));
        const TestImage want = naive::leftRightCheck(d.view(), wr.view(), p);
        leftRightCheck(d.view(), wr.view(), p);
        EXPECT_TRUE(sameImage(want.view(), d.view()));
      }
    }
  }
}

TEST(BruteForceLeftRight, MatchesFormulaOnMatcherOutput) {
  for (int minD : {0, -8}) {
    StereoParams p;
    p.minDisparity = minD;
    p.numDisparities = 16;
    p.blockSize = 5;
    p.textureThreshold = 0;
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      StepScene scene{30, 50, 3, 17, minD + 12, minD + 3};
      const StereoPair pair = stepScenePair(70, 20, scene, seed);
      TestImage d(70, 20, PixelType::S16C1), wr(70, 20, PixelType::S16C1);
      matchBlocks(pair.left.view(), pair.right.view(), {}, p, d.view(), wr.view());
      const TestImage want = naive::leftRightCheck(d.view(), wr.view(), p);
      leftRightCheck(d.view(), wr.view(), p);
      EXPECT_TRUE(sameImage(want.view(), d.view())) << describe(p);
    }
  }
}

// ---------------------------------------------------------------------------
// Speckle filter

TEST(BruteForceSpeckle, MatchesBreadthFirstLabelling) {
  const std::pair<int, int> sizes[] = {{1, 1}, {1, 17}, {17, 1}, {31, 20}, {64, 48}};
  for (const auto& [w, h] : sizes) {
    for (int window : {0, 1, 4, 20, 100}) {
      for (int range : {0, 16, 32, 100}) {
        for (int invalidPercent : {0, 10, 40}) {
          StereoParams p;
          p.minDisparity = -4;
          p.numDisparities = 32;
          p.speckleWindowSize = window;
          p.speckleRange = range;
          const std::uint64_t seed =
              static_cast<std::uint64_t>(w * 1000 + h * 10 + window + range + invalidPercent);
          TestImage d = randomDisparityMap(w, h, p, seed, invalidPercent);
          SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h) + ", " + describe(p) +
                       ", invalid " + std::to_string(invalidPercent) + "%");
          const TestImage want = naive::filterSpeckles(d.view(), p);
          filterSpeckles(d.view(), p);
          EXPECT_TRUE(sameImage(want.view(), d.view()));
        }
      }
    }
  }
}

// Blob membership does not depend on the scan order: a blob joined only
// through a pixel found late (a U shape opened at the top) is one blob.
TEST(BruteForceSpeckle, UShapeIsOneBlob) {
  StereoParams p;
  p.minDisparity = 0;
  p.numDisparities = 16;
  p.speckleWindowSize = 10;  // the U has 13 pixels: kept; each arm alone (4) would go
  p.speckleRange = 0;
  const std::int16_t inv = invalidDisparity(p);
  TestImage d(5, 5, PixelType::S16C1);
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 5; ++x)
      d.at<std::int16_t>(x, y) = inv;
  for (int y = 0; y < 4; ++y) {
    d.at<std::int16_t>(0, y) = 80;
    d.at<std::int16_t>(4, y) = 80;
  }
  for (int x = 0; x < 5; ++x)
    d.at<std::int16_t>(x, 4) = 80;
  d.at<std::int16_t>(2, 1) = 48;  // a lone speckle inside the U: removed
  const TestImage before = d.clone();
  filterSpeckles(d.view(), p);
  EXPECT_TRUE(sameImage(naive::filterSpeckles(before.view(), p).view(), d.view()));
  EXPECT_EQ(d.at<std::int16_t>(0, 0), 80);
  EXPECT_EQ(d.at<std::int16_t>(4, 0), 80);
  EXPECT_EQ(d.at<std::int16_t>(2, 1), inv);
}

// ---------------------------------------------------------------------------
// Median

TEST(BruteForceMedian, MatchesSortedWindowWithFillRule) {
  const std::pair<int, int> sizes[] = {{1, 1}, {2, 3}, {5, 5}, {31, 7}, {33, 20}};
  for (const auto& [w, h] : sizes) {
    for (int k : {3, 5}) {
      for (int minValidToFill : {0, 1, 3, 5, 9, 13, 25}) {
        if (minValidToFill > k * k) continue;
        for (int invalidPercent : {0, 20, 60, 100}) {
          StereoParams sp;
          sp.minDisparity = -3;
          sp.numDisparities = 16;
          const std::int16_t inv = invalidDisparity(sp);
          const std::uint64_t seed = static_cast<std::uint64_t>(w * 977 + h * 31 + k * 7 +
                                                                minValidToFill + invalidPercent);
          const TestImage src = randomDisparityMap(w, h, sp, seed, invalidPercent);
          MedianParams m;
          m.kernelSize = k;
          m.minValidToFill = minValidToFill;
          // 0 means "more than half of the window", written out here.
          const int minValid = minValidToFill > 0 ? minValidToFill : k * k / 2 + 1;
          SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h) + ", kernel " +
                       std::to_string(k) + ", minValidToFill " + std::to_string(minValidToFill) +
                       ", invalid " + std::to_string(invalidPercent) + "%");
          const TestImage want = naive::medianFilter(src.view(), k, minValid, inv);
          TestImage dst(w, h, PixelType::S16C1);
          dst.fillBytes(0x3C);
          medianFilter(src.view(), dst.view(), m, inv);
          EXPECT_TRUE(sameImage(want.view(), dst.view()));
        }
      }
    }
  }
}

TEST(BruteForceMedian, LowerMedianOfEvenCountAndNoNewValues) {
  // Centre valid with 3 of its 4 neighbours in a 2x2 image: n = 4, the lower
  // median is the 2nd smallest (rank (4 - 1) / 2 = 1), never an average.
  StereoParams sp;
  const std::int16_t inv = invalidDisparity(sp);
  TestImage src(2, 2, PixelType::S16C1);
  src.at<std::int16_t>(0, 0) = 10;
  src.at<std::int16_t>(1, 0) = 40;
  src.at<std::int16_t>(0, 1) = 20;
  src.at<std::int16_t>(1, 1) = 30;
  TestImage dst(2, 2, PixelType::S16C1);
  MedianParams m;
  m.kernelSize = 3;
  medianFilter(src.view(), dst.view(), m, inv);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x)
      EXPECT_EQ(dst.at<std::int16_t>(x, y), 20) << x << "," << y;
}

// ---------------------------------------------------------------------------
// Horopter mask

TEST(BruteForceMask, MatchesFormulaForGreyColourAndNoImage) {
  for (int w : {1, 7, 33, 65}) {
    for (int h : {1, 4, 9}) {
      for (int kind = 0; kind < 3; ++kind) {  // no image, U8C1, U8C3
        const std::uint64_t seed = static_cast<std::uint64_t>(w * 100 + h * 3 + kind);
        StereoParams sp;
        sp.minDisparity = -2;
        sp.numDisparities = 32;
        const std::int16_t inv = invalidDisparity(sp);
        const TestImage d = randomDisparityMap(w, h, sp, seed, 20);
        Rng rng(seed);
        std::vector<std::int16_t> thresholds(static_cast<std::size_t>(w));
        for (auto& t : thresholds) {
          const int pick = rng.uniform(0, 9);
          t = pick == 0   ? std::numeric_limits<std::int16_t>::max()
              : pick == 1 ? std::numeric_limits<std::int16_t>::min()
              : pick == 2 ? inv
                          : static_cast<std::int16_t>(rng.uniform(-32, 29 * 16));
        }
        // Some disparities exactly on their column's threshold (inside).
        TestImage dd = d.clone();
        for (int y = 0; y < h; ++y)
          for (int x = 0; x < w; ++x)
            if (rng.chance(15)) dd.at<std::int16_t>(x, y) = thresholds[x];
        TestImage image;
        if (kind > 0)
          image =
              randomImage(w, h, kind == 1 ? PixelType::U8C1 : PixelType::U8C3, seed + 1, 1, 255);
        SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h) + ", image kind " +
                     std::to_string(kind));
        TestImage wantMask, wantSegmented;
        naive::horopterMask(dd.view(), thresholds, inv, kind > 0 ? image.cview() : ConstImageView{},
                            wantMask, wantSegmented);
        TestImage mask(w, h, PixelType::U8C1);
        mask.fillBytes(0x11);
        if (kind == 0) {
          horopterMask(dd.view(), thresholds, inv, mask.view());
        } else {
          TestImage segmented(w, h, image.type());
          segmented.fillBytes(0x22);
          horopterMask(dd.view(), thresholds, inv, mask.view(), image.view(), segmented.view());
          EXPECT_TRUE(sameImage(wantSegmented.view(), segmented.view()));
        }
        EXPECT_TRUE(sameImage(wantMask.view(), mask.view()));
      }
    }
  }
}

}  // namespace
}  // namespace horopter::test
