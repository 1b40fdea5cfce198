// Golden hashes of the scalar reference: FNV-1a 64 of the output pixels (row
// by row, without padding) on a fixed synthetic pair. Any change to what a
// kernel computes changes a hash here, so a change of specification shows in
// review as an edit of this file.
//
// To regenerate after an intended change of output: build, run
//   build/bin/horopter_conformance_tests --gtest_filter='Golden.*'
// and paste the hash each failing expectation prints as its actual value
// (hex64(...) evaluates to "0x..."). The inputs come from the portable
// generator in tests/support (splitmix64), so the values are the same on every
// platform and compiler.
#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "horopter/kernels/kernels.hpp"
#include "horopter/vision/frontend.hpp"
#include "horopter/vision/geometry.hpp"
#include "test_support.hpp"

namespace horopter::test {
namespace {

constexpr int kWidth = 256;
constexpr int kHeight = 160;
constexpr std::uint64_t kSeed = 20240601;

StereoPair goldenPair() {
  return stepScenePair(kWidth, kHeight, StepScene{112, 208, 40, 120, 40, 12}, kSeed);
}

TEST(Golden, FrontendWithDefaultParamsAndMask) {
  const StereoPair pair = goldenPair();
  const TestImage colour = randomImage(kWidth, kHeight, PixelType::U8C3, kSeed + 1, 0, 255);
  StereoFrontend frontend(StereoParams{}, MedianParams{});
  frontend.computeDisparity(pair.left.view(), pair.right.view());
  RectifiedGeometry g;
  g.focalPx = kWidth;
  g.cx = (kWidth - 1) / 2.0;
  g.baseline = 1.0;
  const auto thresholds = horopterThresholds(g, kWidth, fixationFromDisparity(g, g.cx, 26.0));
  frontend.computeMask(thresholds, colour.view());

  EXPECT_EQ(hex64(fnv1a64(frontend.cleanedDisparity().view())), "0xaa34d00087426cf2");
  EXPECT_EQ(hex64(fnv1a64(frontend.disparity().view())), "0x23d084553b3ed95b");
  EXPECT_EQ(hex64(fnv1a64(frontend.mask().view())), "0x2fa093e99920e27d");
  EXPECT_EQ(hex64(fnv1a64(frontend.segmented().view())), "0x33fa7e42a6ef3bbe");
  // The golden output is not degenerate: partly valid, partly inside the zone.
  long valid = 0, inside = 0;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      valid += frontend.disparity().row<std::int16_t>(y)[x] != invalidDisparity(StereoParams{});
      inside += frontend.mask().row<std::uint8_t>(y)[x] == 255;
    }
  }
  EXPECT_GT(valid, kWidth * kHeight / 3);
  EXPECT_LT(valid, kWidth * kHeight);
  EXPECT_GT(inside, kWidth * kHeight / 20);
  EXPECT_LT(inside, valid);
  // The table itself (host floating point, -ffp-contract=off).
  const ConstImageView table{thresholds.data(), kWidth, 1,
                             static_cast<std::ptrdiff_t>(kWidth * sizeof(std::int16_t)),
                             PixelType::S16C1};
  EXPECT_EQ(hex64(fnv1a64(table)), "0x51053f7e5ad09c5c");
}

TEST(Golden, EachKernel) {
  const StereoPair pair = goldenPair();
  const StereoParams p;  // defaults
  TestImage lf(kWidth, kHeight, PixelType::U8C1), rf(kWidth, kHeight, PixelType::U8C1);
  TestImage texture(kWidth, kHeight, PixelType::U8C1);
  prefilterXSobel(pair.left.view(), p.preFilterCap, lf.view(), texture.view());
  prefilterXSobel(pair.right.view(), p.preFilterCap, rf.view(), {});
  EXPECT_EQ(hex64(fnv1a64(lf.view())), "0xfda88d1173703794") << "prefilter: filtered left";
  EXPECT_EQ(hex64(fnv1a64(texture.view())), "0x622b48afc6b434ae") << "prefilter: texture";
  EXPECT_EQ(hex64(fnv1a64(rf.view())), "0x88af7b8a8ecfb582") << "prefilter: filtered right";

  TestImage d(kWidth, kHeight, PixelType::S16C1), wr(kWidth, kHeight, PixelType::S16C1);
  matchBlocks(lf.view(), rf.view(), texture.view(), p, d.view(), wr.view());
  EXPECT_EQ(hex64(fnv1a64(d.view())), "0xf0ad21a076883764") << "matchBlocks: disparity";
  EXPECT_EQ(hex64(fnv1a64(wr.view())), "0x23f2ed6ea745b5f4") << "matchBlocks: winnerRight";

  leftRightCheck(d.view(), wr.view(), p);
  EXPECT_EQ(hex64(fnv1a64(d.view())), "0x581c6e8f9ac24322") << "leftRightCheck";

  filterSpeckles(d.view(), p);
  EXPECT_EQ(hex64(fnv1a64(d.view())), "0xaa34d00087426cf2") << "filterSpeckles";

  TestImage median(kWidth, kHeight, PixelType::S16C1);
  medianFilter(d.view(), median.view(), MedianParams{}, invalidDisparity(p));
  EXPECT_EQ(hex64(fnv1a64(median.view())), "0x23d084553b3ed95b") << "medianFilter";

  std::vector<std::int16_t> thresholds(kWidth);
  for (int u = 0; u < kWidth; ++u)
    thresholds[u] = static_cast<std::int16_t>(16 * (8 + u % 40));
  TestImage mask(kWidth, kHeight, PixelType::U8C1), segmented(kWidth, kHeight, PixelType::U8C1);
  horopterMask(median.view(), thresholds, invalidDisparity(p), mask.view(), pair.left.view(),
               segmented.view());
  EXPECT_EQ(hex64(fnv1a64(mask.view())), "0xdaad14243e0704a2") << "horopterMask: mask";
  EXPECT_EQ(hex64(fnv1a64(segmented.view())), "0xc6f29b54e1873032") << "horopterMask: segmented";
}

// The hash and the generator themselves, so that a change of either is not
// mistaken for a change of the kernels.
TEST(Golden, HashAndGeneratorAreStable) {
  const std::uint8_t bytes[] = {'a'};
  EXPECT_EQ(hex64(fnv1a64({bytes, 1, 1, 1, PixelType::U8C1})), "0xaf63dc4c8601ec8c")
      << "FNV-1a 64 of \"a\" (published test vector)";
  const StereoPair pair = goldenPair();
  EXPECT_EQ(hex64(fnv1a64(pair.left.view())), "0x1dd0aefc05b8d6c0") << "generated left image";
  EXPECT_EQ(hex64(fnv1a64(pair.right.view())), "0x35143b9a12890b6b") << "generated right image";
}

}  // namespace
}  // namespace horopter::test
