// The AVX2 left band (avx2::matchLeftBand, through avx2::matchBlocks)
// against the scalar reference on many random configurations: ranges below,
// across and above zero, band widths from 1 to the whole range, blocks up to
// 33 (past the 16-bit bound: the scalar fallback, and under it with narrow
// inputs), the guard with steps 1 to 7, uniqueness and texture on and off,
// widths just above the smallest the region allows, stripes of rows; and
// avx2::matchLeftBand alone after a region-only pass.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <random>
#include <string>

#include "common/cpu_features.hpp"
#include "horopter/kernels/kernels.hpp"
#include "sad/sad.hpp"
#include "test_support.hpp"

namespace horopter::test {
namespace {

std::string describe(const StereoParams& p) {
  return "minDisparity " + std::to_string(p.minDisparity) + ", numDisparities " +
         std::to_string(p.numDisparities) + ", blockSize " + std::to_string(p.blockSize) +
         ", leftBand " + std::to_string(p.leftBand) + ", uniquenessRatio " +
         std::to_string(p.uniquenessRatio) + ", textureThreshold " +
         std::to_string(p.textureThreshold);
}

TEST(LeftBandAvx2, EqualsScalarOnRandomConfigurations) {
  if (!cpuRunsAvx2Backend()) GTEST_SKIP() << "no AVX2 on this CPU";
  std::mt19937 rng(10217);
  const auto pick = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
  long bandValid = 0, guarded = 0, fast = 0;
  for (int n = 0; n < 400; ++n) {
    StereoParams p;
    p.numDisparities = 16 * pick(1, 4);
    p.minDisparity = pick(-20, 40);
    p.blockSize = 2 * (n % 5 == 0 ? pick(7, 16) : pick(1, 6)) + 1;  // 3..33
    p.leftBand = pick(1, p.numDisparities);
    p.uniquenessRatio = std::array{0, 5, 15, 100, 400}[pick(0, 4)];
    p.textureThreshold = pick(0, 1) * pick(1, 3000);
    BelowRangeGuard guard;
    if (pick(0, 2) == 0) {
      guard.step = pick(1, 7);
      guard.lowest = p.minDisparity - guard.step * pick(0, 6);
      ++guarded;
    }
    const int maxD = p.minDisparity + p.numDisparities - 1;
    const int needed = p.blockSize + std::max(maxD, 0) - std::min(p.minDisparity, 0);
    const int w = needed + pick(0, 3) * pick(0, 40);
    const int h = p.blockSize + pick(1, 9);
    // Narrow value ranges keep large blocks under the 16-bit bound.
    const int hi = pick(0, 2) == 0 ? 255 : pick(3, 60);
    const int shift = pick(std::max(p.minDisparity, 0), std::max(maxD, 0));
    TestImage left = randomImage(w, h, PixelType::U8C1, 1000 + n, 0, hi);
    TestImage right = randomImage(w, h, PixelType::U8C1, 5000 + n, 0, hi);
    for (int y = 0; y < h; ++y)  // mostly a shifted copy, so the band finds matches
      for (int x = 0; x + shift < w; ++x)
        if (pick(0, 7) != 0) right.row<std::uint8_t>(y)[x] = left.row<std::uint8_t>(y)[x + shift];
    const TestImage texture = randomImage(w, h, PixelType::U8C1, 9000 + n, 0, 40);
    fast += static_cast<long>(hi) * p.blockSize * p.blockSize < 0xFFFF;
    SCOPED_TRACE("case " + std::to_string(n) + ": " + std::to_string(w) + "x" + std::to_string(h) +
                 ", guard step " + std::to_string(guard.step) + " down to " +
                 std::to_string(guard.lowest) + ", " + describe(p));
    ASSERT_FALSE(matchRegion(w, h, p).empty());

    TestImage want(w, h, PixelType::S16C1), wantRight(w, h, PixelType::S16C1);
    scalar::matchBlocks(left.view(), right.view(), texture.view(), p, guard, want.view(),
                        wantRight.view(), RowRange{0, h});
    TestImage got(w, h, PixelType::S16C1), gotRight(w, h, PixelType::S16C1);
    const int split = pick(0, h);
    for (const RowRange rows : {RowRange{0, split}, RowRange{split, h}})
      avx2::matchBlocks(left.view(), right.view(), texture.view(), p, guard, got.view(),
                        gotRight.view(), rows);
    ASSERT_TRUE(sameImage(want.view(), got.view())) << "disparity";
    ASSERT_TRUE(sameImage(wantRight.view(), gotRight.view())) << "winnerRight";
    // avx2::matchLeftBand alone (its contract: after a region-only pass; no
    // region least costs, so it costs every candidate of the right pixels).
    StereoParams regionOnly = p;
    regionOnly.leftBand = 0;
    TestImage alone(w, h, PixelType::S16C1), aloneRight(w, h, PixelType::S16C1);
    avx2::matchBlocks(left.view(), right.view(), texture.view(), regionOnly, guard, alone.view(),
                      aloneRight.view(), RowRange{0, h});
    avx2::matchLeftBand(left.view(), right.view(), texture.view(), p, guard, alone.view(),
                        aloneRight.view(), RowRange{0, h});
    ASSERT_TRUE(sameImage(want.view(), alone.view())) << "disparity, band alone";
    ASSERT_TRUE(sameImage(wantRight.view(), aloneRight.view())) << "winnerRight, band alone";
    const MatchRegion region = matchRegion(w, h, p);
    for (int y = region.y0; y < region.y1; ++y)
      for (int x = region.bandX0; x < region.x0; ++x)
        bandValid += want.row<std::int16_t>(y)[x] != invalidDisparity(p);
  }
  EXPECT_GT(bandValid, 3000) << "few valid band pixels: the cases test little";
  EXPECT_GT(guarded, 60);
  EXPECT_GT(fast, 250) << "most cases should take the 16-bit path";
}

}  // namespace
}  // namespace horopter::test
