// Bad input: every public entry point throws horopter::Error (never crashes)
// with a message that names what is wrong.
#include <cstdint>
#include <cstdlib>
#include <initializer_list>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "horopter/core/error.hpp"
#include "horopter/kernels/backend.hpp"
#include "horopter/kernels/kernels.hpp"
#include "horopter/vision/frontend.hpp"
#include "test_support.hpp"

namespace horopter::test {
namespace {

// Runs `f`; success when it throws horopter::Error whose message contains
// every one of `words`.
template <typename F>
::testing::AssertionResult throwsErrorMentioning(F&& f, std::initializer_list<const char*> words) {
  try {
    f();
  } catch (const Error& e) {
    const std::string message = e.what();
    for (const char* word : words) {
      if (message.find(word) == std::string::npos)
        return ::testing::AssertionFailure()
               << "the message \"" << message << "\" does not mention \"" << word << "\"";
    }
    return ::testing::AssertionSuccess() << message;
  } catch (const std::exception& e) {
    return ::testing::AssertionFailure()
           << "threw a std::exception that is not horopter::Error: " << e.what();
  }
  return ::testing::AssertionFailure() << "did not throw";
}

#define EXPECT_ERROR(statement, ...)                                       \
  do {                                                                     \
    EXPECT_THROW(statement, ::horopter::Error);                            \
    EXPECT_TRUE(throwsErrorMentioning([&] { statement; }, {__VA_ARGS__})); \
  } while (0)

// A valid matching setup the tests break one piece at a time.
struct MatchSetup {
  StereoParams params;
  TestImage left, right, texture, disparity, winner;
  MatchSetup(int w = 64, int h = 20) {
    params.numDisparities = 16;
    params.blockSize = 5;
    left = randomImage(w, h, PixelType::U8C1, 1, 0, 255);
    right = randomImage(w, h, PixelType::U8C1, 2, 0, 255);
    texture = randomImage(w, h, PixelType::U8C1, 3, 0, 31);
    disparity = TestImage(w, h, PixelType::S16C1);
    winner = TestImage(w, h, PixelType::S16C1);
  }
  void run() const {
    matchBlocks(left.view(), right.view(), texture.view(), params,
                const_cast<TestImage&>(disparity).view(), const_cast<TestImage&>(winner).view());
  }
};

TEST(BadInput, ValidSetupRuns) {
  MatchSetup s;
  EXPECT_NO_THROW(s.run());
}

TEST(BadInput, MatchSizeMismatch) {
  MatchSetup s;
  s.right = randomImage(63, 20, PixelType::U8C1, 2, 0, 255);
  EXPECT_ERROR(s.run(), "right image", "63x20", "64x20", "same size");
  MatchSetup t;
  t.disparity = TestImage(64, 19, PixelType::S16C1);
  EXPECT_ERROR(t.run(), "disparity output", "same size");
  MatchSetup u;
  u.texture = TestImage(65, 20, PixelType::U8C1);
  EXPECT_ERROR(u.run(), "texture image", "same size");
}

TEST(BadInput, MatchWrongPixelType) {
  MatchSetup s;
  s.left = TestImage(64, 20, PixelType::S16C1);
  EXPECT_ERROR(s.run(), "left image", "S16C1", "U8C1");
  MatchSetup t;
  t.disparity = TestImage(64, 20, PixelType::U8C1);
  EXPECT_ERROR(t.run(), "disparity output", "U8C1", "S16C1");
  MatchSetup u;
  u.right = TestImage(64, 20, PixelType::U8C3);
  EXPECT_ERROR(u.run(), "right image", "U8C3");
}

TEST(BadInput, BlockSize) {
  for (int bad : {8, 2, 1, 0, -5, 257, 1001}) {
    SCOPED_TRACE("blockSize " + std::to_string(bad));
    MatchSetup s;
    s.params.blockSize = bad;
    EXPECT_ERROR(s.run(), "blockSize", std::to_string(bad).c_str());
  }
}

TEST(BadInput, NumDisparities) {
  for (int bad : {0, -16, 20, 8, 1040}) {
    SCOPED_TRACE("numDisparities " + std::to_string(bad));
    MatchSetup s(1200, 10);
    s.params.numDisparities = bad;
    EXPECT_ERROR(s.run(), "numDisparities", std::to_string(bad).c_str());
  }
}

TEST(BadInput, OtherStereoParams) {
  const auto check = [](auto mutate, const char* name) {
    StereoParams p;
    mutate(p);
    EXPECT_ERROR(validate(p), name);
    EXPECT_ERROR((void)StereoFrontend(p, MedianParams{}), name);
  };
  check([](StereoParams& p) { p.preFilterCap = 0; }, "preFilterCap");
  check([](StereoParams& p) { p.preFilterCap = 64; }, "preFilterCap");
  check([](StereoParams& p) { p.textureThreshold = -1; }, "textureThreshold");
  check([](StereoParams& p) { p.uniquenessRatio = -1; }, "uniquenessRatio");
  check([](StereoParams& p) { p.uniquenessRatio = 1001; }, "uniquenessRatio");
  check([](StereoParams& p) { p.speckleWindowSize = -1; }, "speckleWindowSize");
  check([](StereoParams& p) { p.speckleRange = -1; }, "speckleRange");
  check([](StereoParams& p) { p.minDisparity = 2000; }, "minDisparity");
  check([](StereoParams& p) { p.minDisparity = -2100; }, "minDisparity");
  check([](StereoParams& p) { p.preFilterType = static_cast<PreFilterType>(7); }, "preFilterType");
  EXPECT_ERROR(parsePreFilterType("sobel"), "sobel", "xsobel");
}

TEST(BadInput, MedianParams) {
  for (int bad : {4, 1, 7, -3}) {
    MedianParams m;
    m.kernelSize = bad;
    EXPECT_ERROR(validate(m), "kernel size", std::to_string(bad).c_str());
    EXPECT_ERROR((void)StereoFrontend(StereoParams{}, m), "kernel size");
  }
  MedianParams tooMany;
  tooMany.kernelSize = 3;
  tooMany.minValidToFill = 10;
  EXPECT_ERROR(validate(tooMany), "minValidToFill", "10");
  MedianParams negative;
  negative.minValidToFill = -1;
  EXPECT_ERROR(validate(negative), "minValidToFill");
}

TEST(BadInput, EmptyImages) {
  MatchSetup s;
  ConstImageView nullData = s.left.view();
  nullData.data = nullptr;
  EXPECT_ERROR(matchBlocks(nullData, s.right.view(), s.texture.view(), s.params, s.disparity.view(),
                           s.winner.view()),
               "left image", "empty");
  ConstImageView zeroWidth = s.left.view();
  zeroWidth.width = 0;
  EXPECT_ERROR(matchBlocks(zeroWidth, s.right.view(), s.texture.view(), s.params,
                           s.disparity.view(), s.winner.view()),
               "left image", "empty");
  ConstImageView negativeHeight = s.right.view();
  negativeHeight.height = -3;
  EXPECT_ERROR(matchBlocks(s.left.view(), negativeHeight, s.texture.view(), s.params,
                           s.disparity.view(), s.winner.view()),
               "right image", "empty");
  EXPECT_ERROR(prefilterXSobel(ConstImageView{}, 31, s.left.view(), {}), "prefilter input",
               "empty");
  EXPECT_ERROR(filterSpeckles(ImageView{}, s.params), "disparity", "empty");
  StereoFrontend frontend(s.params, MedianParams{});
  EXPECT_ERROR(frontend.computeDisparity(ConstImageView{}, s.right.view()), "left image", "empty");
}

TEST(BadInput, NullOutputs) {
  MatchSetup s;
  EXPECT_ERROR(matchBlocks(s.left.view(), s.right.view(), s.texture.view(), s.params, ImageView{},
                           s.winner.view()),
               "disparity output");
  EXPECT_ERROR(matchBlocks(s.left.view(), s.right.view(), s.texture.view(), s.params,
                           s.disparity.view(), ImageView{}),
               "right-winner output");
  EXPECT_ERROR(prefilterXSobel(s.left.view(), 31, {}, {}), "output");
  MedianParams m;
  EXPECT_ERROR(medianFilter(s.disparity.view(), ImageView{}, m, -16), "median output");
  std::vector<std::int16_t> thresholds(64, 0);
  EXPECT_ERROR(horopterMask(s.disparity.view(), thresholds, -16, ImageView{}), "mask output");
}

TEST(BadInput, MissingTextureWhenTextureCheckIsOn) {
  MatchSetup s;
  s.params.textureThreshold = 10;
  EXPECT_ERROR(
      matchBlocks(s.left.view(), s.right.view(), {}, s.params, s.disparity.view(), s.winner.view()),
      "textureThreshold", "texture");
  s.params.textureThreshold = 0;
  EXPECT_NO_THROW(matchBlocks(s.left.view(), s.right.view(), {}, s.params, s.disparity.view(),
                              s.winner.view()));
}

TEST(BadInput, GuardBelowTheRangeOutOfBounds) {
  MatchSetup s;
  s.params.minDisparity = 8;
  const auto run = [&](BelowRangeGuard guard) {
    matchBlocks(s.left.view(), s.right.view(), s.texture.view(), s.params, guard,
                s.disparity.view(), s.winner.view());
  };
  EXPECT_ERROR(run({-1, 0}), "guard step", "0..1024");
  EXPECT_ERROR(run({kMaxGuardStep + 1, 0}), "guard step");
  EXPECT_ERROR(run({2, 9}), "lowest", "minDisparity");  // above the range's bottom
  EXPECT_ERROR(run({2, 8 - 1025}), "lowest", "minDisparity - 1024");
  EXPECT_NO_THROW(run({2, 0}));
  EXPECT_NO_THROW(run({2, 8})) << "nothing below to check";
  EXPECT_NO_THROW(run({0, 1000})) << "off: lowest is not read";
}

TEST(BadInput, ImageSmallerThanBlock) {
  MatchSetup s(64, 8);
  s.params.blockSize = 9;
  EXPECT_ERROR(s.run(), "64x8", "9x9", "blockSize");
  MatchSetup t(8, 30);
  t.params.blockSize = 9;
  EXPECT_ERROR(t.run(), "8x30", "blockSize");
}

TEST(BadInput, ImageTooNarrowForDisparityRange) {
  for (int minD : {0, 4, -8}) {
    StereoParams p;
    p.numDisparities = 32;
    p.blockSize = 5;
    p.minDisparity = minD;
    // One column less than the narrowest image with a non-empty region.
    const int narrowest = p.blockSize + std::max(minD + 31, 0) - std::min(minD, 0);
    MatchSetup s(narrowest - 1, 12);
    s.params = p;
    SCOPED_TRACE("minDisparity " + std::to_string(minD) + ", width " +
                 std::to_string(narrowest - 1));
    EXPECT_ERROR(s.run(), "numDisparities", std::to_string(narrowest - 1).c_str());
    MatchSetup ok(narrowest, 12);
    ok.params = p;
    EXPECT_NO_THROW(ok.run());
  }
}

// The message of a too-narrow image states the least width ("matching needs
// width >= ... = N"). That statement must be true: width N is the narrowest
// image that is accepted.
TEST(BadInput, NarrowImageMessageStatesTheTrueMinimumWidth) {
  for (int minD : {0, 4, -8, -40}) {
    StereoParams p;
    p.numDisparities = 32;
    p.blockSize = 5;
    p.minDisparity = minD;
    const int narrowest = p.blockSize + std::max(minD + 31, 0) - std::min(minD, 0);
    MatchSetup s(narrowest - 1, 12);
    s.params = p;
    std::string message;
    try {
      s.run();
    } catch (const Error& e) {
      message = e.what();
    }
    ASSERT_FALSE(message.empty()) << "width " << narrowest - 1 << " was accepted";
    const auto equals = message.rfind("= ");
    ASSERT_NE(equals, std::string::npos) << message;
    const int stated = std::atoi(message.c_str() + equals + 2);
    EXPECT_EQ(stated, narrowest) << "minDisparity " << minD
                                 << ": the message says the width must be at least " << stated
                                 << ", but the narrowest accepted width is " << narrowest
                                 << ". Message: " << message;
  }
}

TEST(BadInput, StrideSmallerThanRow) {
  MatchSetup s;
  ConstImageView shortStride = s.left.view();
  shortStride.strideBytes = 63;
  EXPECT_ERROR(matchBlocks(shortStride, s.right.view(), s.texture.view(), s.params,
                           s.disparity.view(), s.winner.view()),
               "left image", "stride", "63");
  ImageView shortOut = s.disparity.view();
  shortOut.strideBytes = 64;  // 64 pixels of 2 bytes need 128
  EXPECT_ERROR(matchBlocks(s.left.view(), s.right.view(), s.texture.view(), s.params, shortOut,
                           s.winner.view()),
               "disparity output", "stride");
  ConstImageView negativeStride = s.left.view();
  negativeStride.strideBytes = -64;
  EXPECT_ERROR(prefilterXSobel(negativeStride, 31, s.texture.view(), {}), "stride");
}

TEST(BadInput, OverlappingBuffers) {
  MatchSetup s;
  // Outputs over the inputs.
  TestImage shared(64, 20, PixelType::S16C1);
  ConstImageView asLeft{shared.view().data, 64, 20, shared.strideBytes(), PixelType::U8C1};
  EXPECT_ERROR(matchBlocks(asLeft, s.right.view(), s.texture.view(), s.params, shared.view(),
                           s.winner.view()),
               "overlap");
  EXPECT_ERROR(matchBlocks(s.left.view(), s.right.view(), s.texture.view(), s.params,
                           s.disparity.view(), s.disparity.view()),
               "overlap");
  // Median in place, or shifted by one row.
  TestImage map(16, 10, PixelType::S16C1);
  MedianParams m;
  EXPECT_ERROR(medianFilter(map.view(), map.view(), m, -16), "overlap");
  TestImage big(16, 11, PixelType::S16C1);
  ImageView top = big.view();
  top.height = 10;
  ImageView shifted = top;
  shifted.data = big.row<std::int16_t>(1);
  EXPECT_ERROR(medianFilter(top, shifted, m, -16), "overlap");
  // Prefilter output over its input.
  TestImage img = randomImage(16, 10, PixelType::U8C1, 5, 0, 255);
  EXPECT_ERROR(prefilterXSobel(img.view(), 31, img.view(), {}), "overlap");
  // Left-right check with the winner map over the disparity.
  EXPECT_ERROR(leftRightCheck(map.view(), map.view(), StereoParams{}), "overlap");
  // Mask over the disparity.
  std::vector<std::int16_t> thresholds(16, 0);
  ImageView maskOverDisparity{map.view().data, 16, 10, map.strideBytes(), PixelType::U8C1};
  EXPECT_ERROR(horopterMask(map.view(), thresholds, -16, maskOverDisparity), "overlap");
}

TEST(BadInput, LeftRightCheckSizesAndTypes) {
  TestImage d(20, 10, PixelType::S16C1), wr(21, 10, PixelType::S16C1);
  EXPECT_ERROR(leftRightCheck(d.view(), wr.view(), StereoParams{}), "right-winner map",
               "same size");
  TestImage u8(20, 10, PixelType::U8C1);
  EXPECT_ERROR(leftRightCheck(u8.view(), d.view(), StereoParams{}), "disparity", "U8C1");
  StereoParams bad;
  bad.blockSize = 4;
  TestImage wr2(20, 10, PixelType::S16C1);
  EXPECT_ERROR(leftRightCheck(d.view(), wr2.view(), bad), "blockSize");
  EXPECT_ERROR(filterSpeckles(d.view(), bad), "blockSize");
  EXPECT_ERROR(filterSpeckles(u8.view(), StereoParams{}), "disparity", "U8C1");
}

TEST(BadInput, MedianKernelAndTypes) {
  TestImage src(20, 10, PixelType::S16C1), dst(20, 10, PixelType::S16C1);
  MedianParams m;
  m.kernelSize = 4;
  EXPECT_ERROR(medianFilter(src.view(), dst.view(), m, -16), "kernel size", "4");
  m.kernelSize = 0;
  EXPECT_ERROR(medianFilter(src.view(), dst.view(), m, -16), "kernelSize 0");
  m.kernelSize = 3;
  TestImage other(19, 10, PixelType::S16C1);
  EXPECT_ERROR(medianFilter(src.view(), other.view(), m, -16), "median output", "same size");
  TestImage u8(20, 10, PixelType::U8C1);
  EXPECT_ERROR(medianFilter(u8.view(), dst.view(), m, -16), "median input", "U8C1");
}

TEST(BadInput, PrefilterCapAndSizes) {
  TestImage src = randomImage(20, 10, PixelType::U8C1, 1, 0, 255);
  TestImage out(20, 10, PixelType::U8C1), small(19, 10, PixelType::U8C1);
  for (int cap : {0, -1, 64, 255})
    EXPECT_ERROR(prefilterXSobel(src.view(), cap, out.view(), {}), "preFilterCap",
                 std::to_string(cap).c_str());
  EXPECT_ERROR(prefilterXSobel(src.view(), 31, small.view(), {}), "prefilter output", "same size");
  EXPECT_ERROR(prefilterXSobel(src.view(), 31, {}, small.view()), "texture output", "same size");
  TestImage s16(20, 10, PixelType::S16C1);
  EXPECT_ERROR(prefilterXSobel(s16.view(), 31, out.view(), {}), "prefilter input", "S16C1");
}

TEST(BadInput, MaskThresholdTableAndImages) {
  TestImage d(20, 6, PixelType::S16C1), mask(20, 6, PixelType::U8C1);
  for (std::size_t n : {std::size_t{0}, std::size_t{19}, std::size_t{21}}) {
    std::vector<std::int16_t> thresholds(n, 0);
    EXPECT_ERROR(horopterMask(d.view(), thresholds, -16, mask.view()), "threshold",
                 std::to_string(n).c_str(), "20 columns");
  }
  std::vector<std::int16_t> thresholds(20, 0);
  TestImage s16(20, 6, PixelType::S16C1), seg16(20, 6, PixelType::S16C1);
  EXPECT_ERROR(horopterMask(d.view(), thresholds, -16, mask.view(), s16.view(), seg16.view()),
               "image to segment", "S16C1");
  TestImage grey(20, 6, PixelType::U8C1), colourOut(20, 6, PixelType::U8C3);
  EXPECT_ERROR(horopterMask(d.view(), thresholds, -16, mask.view(), grey.view(), colourOut.view()),
               "segmented output", "U8C3", "U8C1");
  TestImage smallImage(19, 6, PixelType::U8C1), segmented(20, 6, PixelType::U8C1);
  EXPECT_ERROR(
      horopterMask(d.view(), thresholds, -16, mask.view(), smallImage.view(), segmented.view()),
      "image to segment", "same size");
  EXPECT_ERROR(horopterMask(d.view(), thresholds, -16, mask.view(), {}, segmented.view()),
               "image to segment", "empty");
  TestImage maskSmall(20, 5, PixelType::U8C1);
  EXPECT_ERROR(horopterMask(d.view(), thresholds, -16, maskSmall.view()), "mask output",
               "same size");
}

TEST(BadInput, Backends) {
  EXPECT_ERROR(findBackend("no-such-backend"), "no-such-backend", "scalar", "auto");
  EXPECT_ERROR(findBackend(""), "unknown backend");
  EXPECT_EQ(&findBackend("scalar"), &scalarBackend());

  // HOROPTER_BACKEND overrides "auto"; an unknown name there is an error too.
  const char* saved = std::getenv("HOROPTER_BACKEND");
  const std::string savedValue = saved ? saved : "";
  ::setenv("HOROPTER_BACKEND", "warp-drive", 1);
  EXPECT_ERROR(findBackend("auto"), "warp-drive");
  ::setenv("HOROPTER_BACKEND", "scalar", 1);
  EXPECT_EQ(&findBackend("auto"), &scalarBackend());
  if (saved) {
    ::setenv("HOROPTER_BACKEND", savedValue.c_str(), 1);
  } else {
    ::unsetenv("HOROPTER_BACKEND");
  }
}

TEST(BadInput, BackendWithoutKernel) {
  Backend empty;
  empty.name = "hollow";
  empty.available = true;
  MatchSetup s;
  EXPECT_ERROR(matchBlocks(s.left.view(), s.right.view(), s.texture.view(), s.params,
                           s.disparity.view(), s.winner.view(), empty),
               "hollow", "matching");
  EXPECT_ERROR(prefilterXSobel(s.left.view(), 31, s.texture.view(), {}, empty), "hollow");
}

TEST(BadInput, ImageAndFrontend) {
  EXPECT_ERROR((void)Image(-1, 5, PixelType::U8C1), "negative");
  StereoFrontend frontend(StereoParams{}, MedianParams{});
  std::vector<std::int16_t> thresholds(10, 0);
  EXPECT_ERROR(frontend.computeMask(thresholds), "computeDisparity");
  MatchSetup s(64, 20);
  StereoFrontend small(s.params, MedianParams{});
  EXPECT_ERROR(
      small.computeDisparity(s.left.view(), randomImage(64, 21, PixelType::U8C1, 9, 0, 9).view()),
      "right image", "same size");
}

TEST(BadInput, FrontendMaskAfterFrame) {
  MatchSetup s(64, 20);
  StereoFrontend frontend(s.params, MedianParams{});
  frontend.computeDisparity(s.left.view(), s.right.view());
  std::vector<std::int16_t> shortTable(63, 0);
  EXPECT_ERROR(frontend.computeMask(shortTable), "threshold", "63");
  std::vector<std::int16_t> thresholds(64, 0);
  TestImage wrongSize(60, 20, PixelType::U8C3);
  EXPECT_ERROR(frontend.computeMask(thresholds, wrongSize.view()), "image to segment", "same size");
  TestImage wrongType(64, 20, PixelType::S16C1);
  EXPECT_ERROR(frontend.computeMask(thresholds, wrongType.view()), "image to segment", "S16C1");
}

}  // namespace
}  // namespace horopter::test
