// The OpenCL matcher's left band (StereoParams::leftBand, sad_band.cl after
// either shape of the region's kernels) against the scalar reference, bit
// for bit: both maps, widths from the smallest with a region up,
// ranges at, below and above zero, bands of 1 to numDisparities columns,
// texture and uniqueness on and off, the guard below the range, and rows
// asked for in stripes (each stripe writes its rows alone).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "horopter/kernels/backend.hpp"
#include "horopter/kernels/kernels.hpp"
#include "opencl_support.hpp"
#include "scoped_env.hpp"
#include "test_support.hpp"

namespace horopter::test {
namespace {

struct BandCase {
  int width, height;
  StereoParams params;
  BelowRangeGuard guard;
  bool randomPair;  // independent random images (ties, uniqueness failures)
  int shift;        // else a shifted textured plane
};

// The smallest width whose region has a column: x0 = r + max(maxD, 0) <
// x1 = width - r + min(minD, 0).
int smallestWidth(const StereoParams& p) {
  const int maxD = p.minDisparity + p.numDisparities - 1;
  return p.blockSize + std::max(maxD, 0) - std::min(p.minDisparity, 0);
}

std::vector<BandCase> cases() {
  std::vector<BandCase> out;
  int k = 0;
  for (const int minD : {0, -7, 5, 20}) {
    for (const int numD : {16, 32}) {
      for (const int band : {1, 2, 16, numD}) {
        StereoParams p;
        p.minDisparity = minD;
        p.numDisparities = numD;
        // The settings cycle with different periods, so that they combine.
        p.blockSize = k % 3 == 0 ? 5 : (k % 3 == 1 ? 9 : 3);
        p.leftBand = band;
        // Texture values 0..4 (below): about half the pixels fail.
        p.textureThreshold = k % 2 == 0 ? 0 : p.blockSize * p.blockSize * 2;
        p.uniquenessRatio = (k / 2) % 2 == 0 ? 15 : 0;
        BelowRangeGuard guard;
        if (k % 7 < 3) guard = {1 + k % 4, minD - 9 - k % 5};
        const int w0 = smallestWidth(p);
        const int widths[] = {w0, w0 + 1, w0 + 2, w0 + 5, w0 + 40};
        out.push_back({widths[k % 5], 13 + k % 7, p, guard, (k / 3) % 3 == 2, minD + 3 + k % 11});
        ++k;
      }
    }
  }
  return out;
}

const Backend* openclBackend() {
  for (const Backend* b : registeredBackends())
    if (b->name.rfind("opencl", 0) == 0 && b->available) return b;
  return nullptr;
}

// Matches `c` with `backend` over `stripes` (row ranges), the maps first
// filled with a value no kernel writes, so that unwritten pixels show.
void match(const BandCase& c, const StereoPair& pair, const TestImage& texture,
           const Backend& backend, const std::vector<RowRange>& stripes, TestImage& disparity,
           TestImage& winner) {
  disparity = TestImage(c.width, c.height, PixelType::S16C1);
  winner = TestImage(c.width, c.height, PixelType::S16C1);
  disparity.fillBytes(0x77);
  winner.fillBytes(0x77);
  for (const RowRange& rows : stripes)
    matchBlocks(pair.left.view(), pair.right.view(), texture.view(), c.params, c.guard,
                disparity.view(), winner.view(), backend, rows);
}

TEST(OpenClLeftBand, MatchBlocksEqualsTheScalarReference) {
  HOROPTER_REQUIRE_OPENCL_DEVICE();
  const Backend* device = openclBackend();
  ASSERT_NE(device, nullptr);
  long long bandPixelsValid = 0, bandWinnersChanged = 0;
  for (const char* shape : {"strip", "tiled"}) {
    const ScopedEnv sad("HOROPTER_OPENCL_SAD", shape);
    std::uint64_t seed = 10;
    for (const BandCase& c : cases()) {
      ++seed;
      const StereoParams& p = c.params;
      SCOPED_TRACE(std::string(shape) + ", " + std::to_string(c.width) + "x" +
                   std::to_string(c.height) + ", minD " + std::to_string(p.minDisparity) +
                   ", numD " + std::to_string(p.numDisparities) + ", block " +
                   std::to_string(p.blockSize) + ", band " + std::to_string(p.leftBand) +
                   ", texture " + std::to_string(p.textureThreshold) + ", uniqueness " +
                   std::to_string(p.uniquenessRatio) + ", guard step " +
                   std::to_string(c.guard.step) + " down to " + std::to_string(c.guard.lowest) +
                   (c.randomPair ? ", random pair" : ", shift " + std::to_string(c.shift)));
      StereoPair pair =
          c.randomPair
              ? StereoPair{randomImage(c.width, c.height, PixelType::U8C1, seed, 0, 255),
                           randomImage(c.width, c.height, PixelType::U8C1, seed + 1, 0, 255)}
              : shiftedPair(c.width, c.height, c.shift, Texture::Uniform, seed, 6);
      const TestImage texture = randomImage(c.width, c.height, PixelType::U8C1, seed + 2, 0, 4);
      const int h = c.height;
      const std::vector<std::vector<RowRange>> layouts = {
          {{0, h}}, {{0, h / 3}, {h / 3, h - 4}, {h - 4, h}}, {{3, h - 2}}};
      for (const std::vector<RowRange>& stripes : layouts) {
        SCOPED_TRACE("stripes from row " + std::to_string(stripes.front().begin) + ", " +
                     std::to_string(stripes.size()) + " of them");
        TestImage want, wantWinner, got, gotWinner;
        match(c, pair, texture, scalarBackend(), stripes, want, wantWinner);
        match(c, pair, texture, *device, stripes, got, gotWinner);
        EXPECT_TRUE(sameImage(want.view(), got.view())) << "disparity";
        EXPECT_TRUE(sameImage(wantWinner.view(), gotWinner.view())) << "right winner";
        if (stripes.size() != 1 || stripes.front().begin != 0) continue;
        // That the cases exercise the band: valid band pixels, and right
        // winners the band changes.
        StereoParams off = p;
        off.leftBand = 0;
        TestImage plain(c.width, h, PixelType::S16C1), plainWinner(c.width, h, PixelType::S16C1);
        matchBlocks(pair.left.view(), pair.right.view(), texture.view(), off, c.guard, plain.view(),
                    plainWinner.view(), scalarBackend());
        for (int y = 0; y < h; ++y)
          for (int x = 0; x < c.width; ++x) {
            bandPixelsValid += plain.at<std::int16_t>(x, y) != want.at<std::int16_t>(x, y);
            bandWinnersChanged +=
                plainWinner.at<std::int16_t>(x, y) != wantWinner.at<std::int16_t>(x, y);
          }
      }
    }
  }
  EXPECT_GT(bandPixelsValid, 1000);
  EXPECT_GT(bandWinnersChanged, 1000);
}

// Without a band (leftBand 0) no band kernel runs: the same as the reference
// (the conformance suite covers it widely; here the band's own cases).
TEST(OpenClLeftBand, NoBandEqualsTheScalarReference) {
  HOROPTER_REQUIRE_OPENCL_DEVICE();
  const Backend* device = openclBackend();
  ASSERT_NE(device, nullptr);
  for (const char* shape : {"strip", "tiled"}) {
    const ScopedEnv sad("HOROPTER_OPENCL_SAD", shape);
    for (BandCase c : cases()) {
      c.params.leftBand = 0;
      SCOPED_TRACE(std::string(shape) + ", " + std::to_string(c.width) + " wide");
      const StereoPair pair = shiftedPair(c.width, c.height, c.shift, Texture::Uniform, 7, 6);
      const TestImage texture = randomImage(c.width, c.height, PixelType::U8C1, 8, 0, 4);
      TestImage want, wantWinner, got, gotWinner;
      match(c, pair, texture, scalarBackend(), {{0, c.height}}, want, wantWinner);
      match(c, pair, texture, *device, {{0, c.height}}, got, gotWinner);
      EXPECT_TRUE(sameImage(want.view(), got.view()));
      EXPECT_TRUE(sameImage(wantWinner.view(), gotWinner.view()));
    }
  }
}

}  // namespace
}  // namespace horopter::test
