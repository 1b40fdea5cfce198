// Brute-force versions of every kernel, written from the "Semantics" blocks of
// kernels/*/*_scalar.cpp and nothing else: no sliding sums, no shared code with
// the kernels, the simplest loops. Slow; for small images only.
#pragma once

#include <cstdint>
#include <span>

#include "horopter/core/image.hpp"
#include "horopter/kernels/stereo_params.hpp"
#include "test_support.hpp"

namespace horopter::test::naive {

// floor(a / b) for b > 0, whatever the sign of a.
std::int64_t floorDiv(std::int64_t a, std::int64_t b);

// Outputs are U8C1 images the size of `src`.
void prefilterXSobel(const ConstImageView& src, int cap, TestImage& filtered, TestImage& texture);

// True when every window of every disparity of the range around (x, y) lies
// inside both W x H images (the spec's matching region), decided pixel by
// pixel rather than from the closed form.
bool inMatchRegion(int x, int y, int width, int height, const StereoParams& params);

// SAD cost of one left pixel at one disparity, summed pixel by pixel.
std::int32_t sadCost(const ConstImageView& left, const ConstImageView& right, int x, int y, int d,
                     int radius);

// What happened to the region pixels of one matchBlocks call, so that tests
// can assert that every branch of the spec was exercised.
struct MatchStats {
  long regionPixels = 0;
  long valid = 0;
  long textureRejected = 0;     // invalid because of the texture check
  long uniquenessRejected = 0;  // invalid because of uniqueness (texture passed)
  long subpixelNonZero = 0;     // valid with a non-zero sub-pixel offset
  long tiedWinner = 0;          // another disparity had the winner's cost
  long rangeEndWinner = 0;      // winner at minDisparity or at the largest disparity
  long rightWinners = 0;        // right pixels with a winner
};

struct MatchResult {
  TestImage disparity;    // S16C1, 1/16 px
  TestImage winnerRight;  // S16C1, whole px
  MatchStats stats;
};
MatchResult matchBlocks(const ConstImageView& left, const ConstImageView& right,
                        const ConstImageView& texture, const StereoParams& params);

// Returns the checked copy of `disparity`.
TestImage leftRightCheck(const ConstImageView& disparity, const ConstImageView& winnerRight,
                         const StereoParams& params);

// Breadth-first labelling of the blobs, then invalidation of the small ones.
TestImage filterSpeckles(const ConstImageView& disparity, const StereoParams& params);

TestImage medianFilter(const ConstImageView& src, int kernelSize, int minValid,
                       std::int16_t invalid);

// mask is U8C1; segmented (same type as image) only when image is not empty.
void horopterMask(const ConstImageView& disparity, std::span<const std::int16_t> thresholds,
                  std::int16_t invalid, const ConstImageView& image, TestImage& mask,
                  TestImage& segmented);

}  // namespace horopter::test::naive
