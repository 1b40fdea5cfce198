// zoneSearchRange: the range a frame searches follows its zone, never
// leaves out a disparity that can reach a threshold (less the margin), and
// keeps the full range's top; the options are checked against their table.
// The guard below the range removes a far textured plane that the range
// alone would call inside.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "horopter/core/error.hpp"
#include "horopter/vision/frontend.hpp"
#include "horopter/vision/zone_search.hpp"
#include "test_support.hpp"

namespace horopter::test {
namespace {

// Zone search on, without the guard below the range unless asked.
ZoneSearch on(int margin = 4, int maxDisparity = 0) {
  ZoneSearch z;
  z.enabled = 1;
  z.marginPx = margin;
  z.maxDisparity = maxDisparity;
  z.guardStep = 0;
  return z;
}

std::vector<std::int16_t> flat(int thresholdPx16, int width = 8) {
  return std::vector<std::int16_t>(static_cast<std::size_t>(width),
                                   static_cast<std::int16_t>(thresholdPx16));
}

TEST(ZoneSearch, OffOrWithoutThresholdsSearchesTheFullRange) {
  const StereoParams p;
  EXPECT_EQ(zoneSearchRange(p, flat(16 * 40), ZoneSearch{}), fullRange(p));
  EXPECT_EQ(zoneSearchRange(p, {}, on()), fullRange(p));
}

TEST(ZoneSearch, StartsBelowTheSmallestThresholdAndKeepsTheTop) {
  const StereoParams p;  // 0..63
  // Smallest threshold 36 px: a winner of 36 can reach it, 4 px margin: 32.
  std::vector<std::int16_t> t = flat(16 * 50);
  t[3] = 16 * 36;
  EXPECT_EQ(zoneSearchRange(p, t, on()), (SearchRange{32, 32}));
  // 36 px + 9/16: a winner of 36 reports at most 36 + 8/16, so 37 is the
  // lowest that can reach it; 33 after the margin, rounded to 16 steps: 32.
  t[3] = 16 * 36 + 9;
  EXPECT_EQ(zoneSearchRange(p, t, on()), (SearchRange{32, 32}));
  t[3] = 16 * 36 + 8;  // 36 + 8/16 is reachable from 36
  EXPECT_EQ(zoneSearchRange(p, t, on(0)), (SearchRange{32, 32}));
  t[3] = 16 * 48 + 9;  // lowest winner 49: 15 disparities, rounded up to 16
  EXPECT_EQ(zoneSearchRange(p, t, on(0)), (SearchRange{48, 16}));
  // Past the full range's top: near hands.
  EXPECT_EQ(zoneSearchRange(p, flat(16 * 36), on(4, 127)), (SearchRange{32, 96}));
}

TEST(ZoneSearch, NeverStartsBelowTheConfiguredMinimum) {
  StereoParams p;
  p.minDisparity = 5;
  p.numDisparities = 48;  // 5..52
  EXPECT_EQ(zoneSearchRange(p, flat(16), on()), fullRange(p));
  EXPECT_EQ(zoneSearchRange(p, flat(-400), on()), fullRange(p));
  // 12 px after the margin would give 12..52, 41 disparities: 48 from 5.
  EXPECT_EQ(zoneSearchRange(p, flat(16 * 16), on()), fullRange(p));
  // A top just above the minimum still searches 16 disparities.
  EXPECT_EQ(zoneSearchRange(p, flat(16 * 30), on(0, 9)), (SearchRange{5, 16}));
}

TEST(ZoneSearch, EveryReachableDisparityOfEveryColumnIsSearched) {
  const StereoParams p;
  for (int margin : {0, 3, 8}) {
    for (int t = -40; t < 16 * 70; t += 7) {
      std::vector<std::int16_t> th = flat(16 * 60);
      th[5] = static_cast<std::int16_t>(t);
      const SearchRange r = zoneSearchRange(p, th, on(margin));
      ASSERT_EQ(r.numDisparities % 16, 0);
      ASSERT_GE(r.minDisparity, p.minDisparity);
      ASSERT_EQ(r.minDisparity + r.numDisparities, 64) << "the top stays";
      // The lowest winner whose sub-pixel value (at most 16 d + 8) reaches
      // t is searched with `margin` more below it, and the range starts
      // less than 16 below that (it is rounded, not padded).
      int lowest = 0;
      while (lowest < 63 && 16 * lowest + 8 < std::min(t, 16 * 60))
        ++lowest;
      // ... but never above the top's last 16, nor below the minimum.
      const int wanted = std::max(0, std::min(lowest - margin, 48));
      ASSERT_LE(r.minDisparity, wanted) << t;
      ASSERT_GT(r.minDisparity, wanted - 16) << t;
    }
  }
}

TEST(ZoneSearch, OptionsAreCheckedAgainstTheirTable) {
  const StereoParams p;
  EXPECT_NO_THROW(validate(on(), p));
  EXPECT_THROW(validate(on(300), p), Error);
  ZoneSearch bad = on();
  bad.enabled = 2;
  EXPECT_THROW(validate(bad, p), Error);
  StereoParams shifted;
  shifted.minDisparity = 20;
  EXPECT_THROW(validate(on(4, 10), shifted), Error);  // a top below the bottom
  EXPECT_THROW(validate(on(4, 4000), p), Error);
  EXPECT_EQ(largestDisparity(p, on(4, 127)), 127);
  EXPECT_EQ(largestDisparity(p, on()), 63);
  EXPECT_EQ(largestDisparity(p, ZoneSearch{0, 4, 127}), 63) << "off: the full range";
  ZoneSearch guard = on();
  guard.guardStep = 65;
  EXPECT_THROW(validate(guard, p), Error);
  EXPECT_EQ(zoneSearchOptions().size(), 4u);
}

TEST(ZoneSearch, TheRangeCarriesTheGuardOnlyWhenSomethingLiesBelowIt) {
  const StereoParams p;  // 0..63
  ZoneSearch z = on();
  z.guardStep = 3;
  EXPECT_EQ(zoneSearchRange(p, flat(16 * 40), z), (SearchRange{32, 32, 3}));
  EXPECT_EQ(zoneSearchRange(p, flat(16 * 10), z), (SearchRange{0, 64})) << "the full range";
  z.enabled = 0;
  EXPECT_EQ(zoneSearchRange(p, flat(16 * 40), z), fullRange(p));
  EXPECT_EQ(guardBelow(p, {32, 32, 3}).step, 3);
  EXPECT_EQ(guardBelow(p, {32, 32, 3}).lowest, 0);
  EXPECT_EQ(guardBelow(p, {32, 32}).step, 0);
  EXPECT_THROW(checkSearchRange(p, {32, 32, -1}), Error);
  EXPECT_THROW(checkSearchRange(p, {32, 32, kMaxGuardStep + 1}), Error);
}

// A far wall of repeating texture at 13 px, below a zone whose range starts
// at 16: the full range finds 13 (outside the zone); the range alone finds
// the texture's repeat at 13 + 40 = 53 (inside); the guard, checking 13,
// 10, ... below the range, invalidates those pixels.
TEST(ZoneSearch, TheGuardRemovesAFarTexturedPlaneBelowTheRange) {
  const int w = 220, h = 60, disparity = 13, period = 40;
  Rng rng(2024);
  std::vector<int> tile(static_cast<std::size_t>(period) * h);
  for (int& v : tile)
    v = rng.uniform(40, 215);
  TestImage left(w, h, PixelType::U8C1), right(w, h, PixelType::U8C1);
  // Faint noise that does not repeat, so the full range has one best match.
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w + disparity; ++x) {
      const int v = tile[static_cast<std::size_t>(y * period + x % period)] + rng.uniform(-6, 6);
      if (x < w) left.view().row<std::uint8_t>(y)[x] = static_cast<std::uint8_t>(v);
      if (x - disparity >= 0)
        right.view().row<std::uint8_t>(y)[x - disparity] = static_cast<std::uint8_t>(v);
    }
  for (int x = w - disparity; x < w; ++x)  // the right view's last columns: unseen
    for (int y = 0; y < h; ++y)
      right.view().row<std::uint8_t>(y)[x] = static_cast<std::uint8_t>(rng.uniform(0, 255));

  const StereoParams p;  // 0..63
  const std::vector<std::int16_t> thresholds = flat(16 * 20, w);
  ZoneSearch z = on(4);
  z.guardStep = 3;
  const SearchRange guarded = zoneSearchRange(p, thresholds, z);
  ASSERT_EQ(guarded, (SearchRange{16, 48, 3}));
  const SearchRange plain{guarded.minDisparity, guarded.numDisparities};

  const auto inside = [&](SearchRange range) {
    StereoFrontend frontend(p, MedianParams{});
    frontend.computeDisparity(left.view(), right.view(), range);
    frontend.computeMask(thresholds);
    int n = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        n += frontend.mask().row<std::uint8_t>(y)[x] != 0;
    return n;
  };
  const int region = (w - 4 - 67) * (h - 8);  // the matcher's columns and rows
  const int full = inside(fullRange(p)), limited = inside(plain), withGuard = inside(guarded);
  EXPECT_LT(full, region / 100) << "the full range puts the wall outside";
  EXPECT_GT(limited, region / 2) << "the range alone calls the wall inside";
  EXPECT_LT(withGuard, region / 100) << "the guard removes it";
}

// A left band wider than a frame's range would fail validation on that
// frame (horopter run --zone-search 1 --left-band 64 did, on frame 0): the
// range's parameters ask for at most all of its disparities.
TEST(ZoneSearch, TheLeftBandNeverAsksForMoreThanTheRange) {
  StereoParams full;
  full.numDisparities = 96;
  full.leftBand = 64;
  const StereoParams narrow = withRange(full, {48, 32});
  EXPECT_EQ(narrow.leftBand, 32);
  EXPECT_NO_THROW(validate(narrow));
  EXPECT_EQ(withRange(full, {0, 96}).leftBand, 64);
  full.leftBand = 0;
  EXPECT_EQ(withRange(full, {48, 32}).leftBand, 0);
}

TEST(ZoneSearch, CheckSearchRangeRefusesRangesBelowTheMinimumOrOddSizes) {
  const StereoParams p;
  EXPECT_NO_THROW(checkSearchRange(p, {16, 48}));
  EXPECT_THROW(checkSearchRange(p, {-1, 64}), Error);
  EXPECT_THROW(checkSearchRange(p, {16, 40}), Error);
  EXPECT_THROW(checkSearchRange(p, {16, 0}), Error);
}

}  // namespace
}  // namespace horopter::test
