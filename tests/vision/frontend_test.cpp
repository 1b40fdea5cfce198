// StereoFrontend: the chain equals the kernels called one by one, buffers are
// reused correctly across frames and sizes, masks and segmentation.
#include <unistd.h>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "horopter/kernels/kernels.hpp"
#include "horopter/vision/frontend.hpp"
#include "horopter/vision/geometry.hpp"
#include "horopter/vision/opencv.hpp"
#include "horopter/vision/zone_search.hpp"
#include "io/disparity_images.hpp"
#include "test_support.hpp"

namespace horopter::test {
namespace {

struct Chain {
  TestImage cleaned, final;
};

// The front end's chain, kernel by kernel, written from frontend.hpp.
Chain runKernels(const ConstImageView& left, const ConstImageView& right, const StereoParams& p,
                 const MedianParams& m) {
  const int w = left.width, h = left.height;
  TestImage lf(w, h, PixelType::U8C1), rf(w, h, PixelType::U8C1), tex(w, h, PixelType::U8C1);
  ConstImageView matchLeft = left, matchRight = right, texture{};
  if (p.preFilterType == PreFilterType::XSobel) {
    prefilterXSobel(left, p.preFilterCap, lf.view(), tex.view());
    prefilterXSobel(right, p.preFilterCap, rf.view(), {});
    matchLeft = lf.view();
    matchRight = rf.view();
  } else if (p.preFilterType == PreFilterType::NormalizedResponse) {
    prefilterNormalized(left, p.preFilterCap, p.preFilterSize, lf.view(), tex.view());
    prefilterNormalized(right, p.preFilterCap, p.preFilterSize, rf.view(), {});
    matchLeft = lf.view();
    matchRight = rf.view();
  } else {
    prefilterXSobel(left, p.preFilterCap, {}, tex.view());
  }
  if (p.textureThreshold > 0) texture = tex.view();
  Chain out{TestImage(w, h, PixelType::S16C1), TestImage()};
  TestImage wr(w, h, PixelType::S16C1);
  matchBlocks(matchLeft, matchRight, texture, p, out.cleaned.view(), wr.view());
  leftRightCheck(out.cleaned.view(), wr.view(), p);
  filterSpeckles(out.cleaned.view(), p);
  if (m.kernelSize > 0) {
    out.final = TestImage(w, h, PixelType::S16C1);
    medianFilter(out.cleaned.view(), out.final.view(), m, invalidDisparity(p));
  } else {
    out.final = out.cleaned.clone();
  }
  return out;
}

struct Setting {
  const char* what;
  StereoParams p;
  MedianParams m;
};

std::vector<Setting> settings() {
  std::vector<Setting> s;
  s.push_back({"defaults", StereoParams{}, MedianParams{}});
  StereoParams p;
  p.numDisparities = 32;
  p.preFilterType = PreFilterType::None;
  s.push_back({"no prefilter, texture check on", p, MedianParams{}});
  p.textureThreshold = 0;
  MedianParams m3;
  m3.kernelSize = 3;
  s.push_back({"no prefilter, no texture check, median 3", p, m3});
  StereoParams q;
  q.numDisparities = 32;
  q.minDisparity = -8;
  q.blockSize = 7;
  q.disp12MaxDiff = -1;
  q.speckleWindowSize = 0;
  MedianParams off;
  off.kernelSize = 0;
  s.push_back({"negative range, no left-right check, no speckles, no median", q, off});
  StereoParams r;
  r.numDisparities = 48;
  r.blockSize = 11;
  r.uniquenessRatio = 0;
  r.disp12MaxDiff = 0;
  r.speckleWindowSize = 400;
  r.speckleRange = 16;
  MedianParams fill;
  fill.minValidToFill = 3;
  s.push_back({"block 11, strict check, big speckles, eager fill", r, fill});
  // Shifted ranges with the median on: the invalid marker is not -16.
  StereoParams shifted;
  shifted.numDisparities = 32;
  shifted.minDisparity = -8;
  s.push_back({"range -8..23, median 5", shifted, MedianParams{}});
  shifted.minDisparity = 3;
  s.push_back({"range 3..34, median 3", shifted, m3});
  StereoParams normalized = stereoBMDefaults(32, 15);
  normalized.preFilterType = PreFilterType::NormalizedResponse;
  normalized.preFilterSize = 7;
  s.push_back({"StereoBM's defaults, normalized response of size 7", normalized, off});
  return s;
}

TEST(Frontend, ChainEqualsKernelsOneByOne) {
  const StereoPair pair = stepScenePair(200, 90, StepScene{100, 170, 20, 70, 30, 5}, 31);
  for (const Setting& s : settings()) {
    SCOPED_TRACE(s.what);
    StereoFrontend frontend(s.p, s.m);
    const Image& out = frontend.computeDisparity(pair.left.view(), pair.right.view());
    const Chain want = runKernels(pair.left.view(), pair.right.view(), s.p, s.m);
    EXPECT_TRUE(sameImage(want.cleaned.view(), frontend.cleanedDisparity().view()));
    EXPECT_TRUE(sameImage(want.final.view(), out.view()));
    EXPECT_EQ(&out, &frontend.disparity());
    EXPECT_EQ(frontend.stereoParams().numDisparities, s.p.numDisparities);
    EXPECT_EQ(frontend.medianParams().kernelSize, s.m.kernelSize);
    // The defaults are FrontendDefaults': the auto backend, every hardware thread.
    EXPECT_EQ(&frontend.backend(), &findBackend(FrontendDefaults::backend));
    EXPECT_EQ(frontend.threads(), resolveThreads(FrontendDefaults::threads));
    const FrontendTimings& t = frontend.timings();
    for (double ms : {t.prefilter, t.match, t.cleanup, t.median, t.mask})
      EXPECT_GE(ms, 0);
    EXPECT_DOUBLE_EQ(t.total(), t.prefilter + t.match + t.cleanup + t.median + t.mask);
  }
}

// Rewrites `from` as `to` in an S16C1 image.
void replaceValue(TestImage& map, std::int16_t from, std::int16_t to) {
  const ImageView v = map.view();
  for (int y = 0; y < v.height; ++y) {
    std::int16_t* row = v.row<std::int16_t>(y);
    std::replace(row, row + v.width, from, to);
  }
}

// Zone-limited matching: a search range runs the chain over that range, and
// invalid pixels carry the configured range's marker.
// setStereoParams: the next frame runs with the new parameters; a bad set
// throws naming the parameter and leaves the old one in place.
TEST(Frontend, SetStereoParamsTakesEffectOrKeepsTheOldOnes) {
  const StereoPair pair = stepScenePair(200, 90, StepScene{100, 170, 20, 70, 30, 5}, 31);
  StereoParams a;
  StereoParams b = a;
  b.numDisparities = 32;
  b.preFilterType = PreFilterType::NormalizedResponse;
  StereoFrontend frontend(a, MedianParams{}, scalarBackend(), 1);
  StereoFrontend wantB(b, MedianParams{}, scalarBackend(), 1);
  frontend.setStereoParams(b);
  frontend.computeDisparity(pair.left.view(), pair.right.view());
  wantB.computeDisparity(pair.left.view(), pair.right.view());
  EXPECT_TRUE(sameImage(wantB.disparity().view(), frontend.disparity().view()));
  StereoParams bad = b;
  bad.preFilterSize = 4;
  try {
    frontend.setStereoParams(bad);
    ADD_FAILURE() << "an even preFilterSize was taken";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("preFilterSize"), std::string::npos) << e.what();
  }
  EXPECT_EQ(frontend.stereoParams().preFilterSize, b.preFilterSize);
  EXPECT_EQ(frontend.stereoParams().numDisparities, 32);
}

TEST(Frontend, SearchRangeRunsTheChainOverThatRange) {
  const StereoPair pair = stepScenePair(200, 90, StepScene{100, 170, 20, 70, 40, 12}, 37);
  const StereoParams p;  // 0..63
  for (const Setting& s : settings()) {
    if (s.p.minDisparity != 0 || s.p.numDisparities != 64) continue;
    for (const SearchRange range : {SearchRange{16, 48}, SearchRange{32, 32}, SearchRange{8, 80}}) {
      SCOPED_TRACE(s.what + std::string(", range from ") + std::to_string(range.minDisparity));
      StereoFrontend frontend(s.p, s.m);
      const Image& out = frontend.computeDisparity(pair.left.view(), pair.right.view(), range);
      Chain want = runKernels(pair.left.view(), pair.right.view(), withRange(s.p, range), s.m);
      const std::int16_t rangeInvalid = invalidDisparity(withRange(s.p, range));
      replaceValue(want.cleaned, rangeInvalid, invalidDisparity(s.p));
      replaceValue(want.final, rangeInvalid, invalidDisparity(s.p));
      EXPECT_TRUE(sameImage(want.cleaned.view(), frontend.cleanedDisparity().view()));
      EXPECT_TRUE(sameImage(want.final.view(), out.view()));
      EXPECT_EQ(frontend.lastRange(), range);
      int valid = 0;
      for (int y = 0; y < out.height(); ++y)
        for (int x = 0; x < out.width(); ++x) {
          const int d = out.row<std::int16_t>(y)[x];
          if (d == invalidDisparity(s.p)) continue;
          ++valid;
          EXPECT_GE(d, range.minDisparity * kDisparityScale) << x << "," << y;
        }
      EXPECT_GT(valid, 1000);
    }
  }
  StereoFrontend frontend(p, MedianParams{});
  frontend.computeDisparity(pair.left.view(), pair.right.view());
  EXPECT_EQ(frontend.lastRange(), fullRange(p));
  EXPECT_THROW(frontend.computeDisparity(pair.left.view(), pair.right.view(), {-16, 64}), Error);
  EXPECT_THROW(frontend.computeDisparity(pair.left.view(), pair.right.view(), {16, 40}), Error);
}

TEST(Frontend, StridedAndRoiInputsGiveTheSameResult) {
  const StereoPair pair = stepScenePair(150, 60, StepScene{80, 130, 10, 50, 20, 4}, 5);
  StereoParams p;
  p.numDisparities = 32;
  StereoFrontend tight(p, MedianParams{});
  tight.computeDisparity(pair.left.view(), pair.right.view());
  for (const Layout& layout : kLayouts) {
    const TestImage l = pair.left.clone(layout), r = pair.right.clone(layout);
    StereoFrontend other(p, MedianParams{});
    other.computeDisparity(l.view(), r.view());
    EXPECT_TRUE(sameImage(tight.disparity().view(), other.disparity().view())) << layout.name;
    EXPECT_TRUE(l.canariesIntact());
    EXPECT_TRUE(r.canariesIntact());
  }
}

// One front end over frames of changing content and size gives what a fresh
// one gives: nothing from an earlier frame leaks into a later one.
TEST(Frontend, ReusedAcrossFramesAndSizes) {
  StereoParams p;
  p.numDisparities = 32;
  StereoFrontend reused(p, MedianParams{});
  // Same size twice, then changes of both sides, of the height only and of
  // the width only.
  const std::pair<int, int> sizes[] = {{120, 50}, {120, 50}, {181, 77}, {120, 50},
                                       {120, 64}, {96, 64},  {96, 40}};
  std::uint64_t seed = 1;
  for (const auto& [w, h] : sizes) {
    SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h));
    const StereoPair pair = stepScenePair(w, h, StepScene{w / 2, w - 10, 8, h - 8, 25, 3}, seed++);
    const TestImage colour = randomImage(w, h, PixelType::U8C3, seed, 0, 255);
    std::vector<std::int16_t> thresholds(static_cast<std::size_t>(w));
    for (int u = 0; u < w; ++u)
      thresholds[u] = static_cast<std::int16_t>(16 * (5 + u % 20));
    reused.computeDisparity(pair.left.view(), pair.right.view());
    reused.computeMask(thresholds, seed % 2 ? colour.view() : pair.left.view());
    StereoFrontend fresh(p, MedianParams{});
    fresh.computeDisparity(pair.left.view(), pair.right.view());
    fresh.computeMask(thresholds, seed % 2 ? colour.view() : pair.left.view());
    EXPECT_TRUE(sameImage(fresh.disparity().view(), reused.disparity().view()));
    EXPECT_TRUE(sameImage(fresh.cleanedDisparity().view(), reused.cleanedDisparity().view()));
    EXPECT_TRUE(sameImage(fresh.mask().view(), reused.mask().view()));
    EXPECT_TRUE(sameImage(fresh.segmented().view(), reused.segmented().view()));
  }
}

TEST(Frontend, MaskAndSegmentationFollowTheFinalDisparity) {
  const int w = 160, h = 64;
  const StereoPair pair = stepScenePair(w, h, StepScene{80, 140, 12, 52, 28, 6}, 77);
  StereoParams p;
  p.numDisparities = 32;
  StereoFrontend frontend(p, MedianParams{});
  frontend.computeDisparity(pair.left.view(), pair.right.view());
  RectifiedGeometry g{static_cast<double>(w), (w - 1) / 2.0, 1.0};
  // Fixate between the two depths: the near square is inside, the background out.
  const auto thresholds = horopterThresholds(g, w, fixationFromDisparity(g, g.cx, 17.0));
  const TestImage colour = randomImage(w, h, PixelType::U8C3, 5, 1, 255);
  frontend.computeMask(thresholds, colour.view());
  ASSERT_EQ(frontend.segmented().type(), PixelType::U8C3);
  TestImage mask(w, h, PixelType::U8C1), segmented(w, h, PixelType::U8C3);
  horopterMask(frontend.disparity().view(), thresholds, invalidDisparity(p), mask.view(),
               colour.view(), segmented.view());
  EXPECT_TRUE(sameImage(mask.view(), frontend.mask().view()));
  EXPECT_TRUE(sameImage(segmented.view(), frontend.segmented().view()));
  long nearInside = 0, nearTotal = 0, farInside = 0, farTotal = 0;
  for (int y = 20; y < 44; ++y) {
    for (int x = 90; x < 130; ++x) {
      ++nearTotal;
      nearInside += frontend.mask().row<std::uint8_t>(y)[x] == 255;
    }
    for (int x = 36; x < 52; ++x) {
      ++farTotal;
      farInside += frontend.mask().row<std::uint8_t>(y)[x] == 255;
    }
  }
  EXPECT_EQ(nearInside, nearTotal) << "the near square is inside the circle";
  EXPECT_EQ(farInside, 0) << "the background is outside";

  // A grey image gives a grey segmentation.
  frontend.computeMask(thresholds, pair.left.view());
  EXPECT_EQ(frontend.segmented().type(), PixelType::U8C1);
  TestImage grey(w, h, PixelType::U8C1);
  horopterMask(frontend.disparity().view(), thresholds, invalidDisparity(p), mask.view(),
               pair.left.view(), grey.view());
  EXPECT_TRUE(sameImage(grey.view(), frontend.segmented().view()));
}

TEST(Frontend, WritesItsOutputsAsImages) {
  const int w = 120, h = 48;
  const StereoPair pair = stepScenePair(w, h, StepScene{60, 100, 10, 38, 20, 4}, 9);
  StereoParams p;
  p.numDisparities = 32;
  StereoFrontend frontend(p, MedianParams{});
  frontend.computeDisparity(pair.left.view(), pair.right.view());
  std::vector<std::int16_t> thresholds(w, static_cast<std::int16_t>(16 * 12));
  const TestImage colour = randomImage(w, h, PixelType::U8C3, 3, 0, 255);
  frontend.computeMask(thresholds, colour.view());
  const auto dir = std::filesystem::temp_directory_path() /
                   ("horopter-test-" + std::to_string(::getpid()) + "-outputs");
  std::filesystem::remove_all(dir);
  writeFrontendOutputs(dir.string(), frontend);

  // disparity.png: 16-bit, 1/16 px; invalid and non-positive disparities are 0.
  const cv::Mat png = cv::imread((dir / "disparity.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(png.type(), CV_16UC1);
  ASSERT_EQ(png.cols, w);
  ASSERT_EQ(png.rows, h);
  const std::int16_t inv = invalidDisparity(p);
  long invalid = 0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const std::int16_t d = frontend.disparity().row<std::int16_t>(y)[x];
      const int want = (d == inv || d <= 0) ? 0 : d;
      ASSERT_EQ(png.at<std::uint16_t>(y, x), want) << x << "," << y;
      invalid += d == inv;
    }
  }
  EXPECT_GT(invalid, 0);
  // disparity16.png and disparity.pfm give back the map itself, invalid kept.
  const cv::Mat back16 = readDisparity16Png((dir / "disparity16.png").string(), inv);
  EXPECT_TRUE(sameImage(frontend.disparity().view(), viewOf(back16)));
  const cv::Mat pfm = readPfm((dir / "disparity.pfm").string());
  ASSERT_EQ(pfm.size(), cv::Size(w, h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::int16_t d = frontend.disparity().row<std::int16_t>(y)[x];
      if (d == inv)
        ASSERT_TRUE(std::isinf(pfm.at<float>(y, x))) << x << "," << y;
      else
        ASSERT_EQ(pfm.at<float>(y, x), d / 16.0f) << x << "," << y;
    }
  // disparity_color.png: black where invalid, coloured elsewhere, but for
  // the colour scale in its corner.
  const cv::Mat colourPng = cv::imread((dir / "disparity_color.png").string(), cv::IMREAD_COLOR);
  ASSERT_EQ(colourPng.size(), cv::Size(w, h));
  const cv::Rect scale = disparityScaleRect(colourPng.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (scale.contains({x, y})) continue;
      const bool isInvalid = frontend.disparity().row<std::int16_t>(y)[x] == inv;
      const cv::Vec3b c = colourPng.at<cv::Vec3b>(y, x);
      ASSERT_EQ(c == cv::Vec3b(0, 0, 0), isInvalid) << x << "," << y;
    }
  const cv::Mat maskPng = cv::imread((dir / "mask.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(maskPng.type(), CV_8UC1);
  EXPECT_TRUE(sameImage(frontend.mask().view(), viewOf(maskPng)));
  const cv::Mat segPng = cv::imread((dir / "segmented.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(segPng.type(), CV_8UC3);
  EXPECT_TRUE(sameImage(frontend.segmented().view(), viewOf(segPng)));
  std::filesystem::remove_all(dir);
}

// disparity.png keeps positive disparities and writes 0 for invalid and
// non-positive ones.
TEST(Frontend, DisparityPngWritesUnknownAsZero) {
  const std::int16_t inv = -9 * 16;
  const std::int16_t row[7] = {-40, inv, 0, 5, 300, 32767, -1};
  const auto path = std::filesystem::temp_directory_path() /
                    ("horopter-test-" + std::to_string(::getpid()) + "-disparity.png");
  writeDisparityPng(path.string(), {row, 7, 1, sizeof row, PixelType::S16C1}, inv);
  const cv::Mat png = cv::imread(path.string(), cv::IMREAD_UNCHANGED);
  std::filesystem::remove(path);
  ASSERT_EQ(png.type(), CV_16UC1);
  ASSERT_EQ(png.cols, 7);
  const int want[7] = {0, 0, 0, 5, 300, 32767, 0};
  for (int x = 0; x < 7; ++x)
    EXPECT_EQ(png.at<std::uint16_t>(0, x), want[x]) << x;
}

std::filesystem::path tempFile(const std::string& name) {
  return std::filesystem::temp_directory_path() /
         ("horopter-test-" + std::to_string(::getpid()) + "-" + name);
}

// disparity16.png keeps negative and sub-pixel disparities, invalid apart:
// d16 + 32768, 0 = invalid.
TEST(Frontend, Disparity16PngRoundTripsSignedSubpixel) {
  const std::int16_t inv = -33 * 16;
  const std::int16_t row[10] = {-40, inv, 0, 5, 300, 32767, -1, -32 * 16, -32767, -32768};
  const auto path = tempFile("disparity16.png");
  writeDisparity16Png(path.string(), {row, 10, 1, sizeof row, PixelType::S16C1}, inv);
  const cv::Mat png = cv::imread(path.string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(png.type(), CV_16UC1);
  const int want[10] = {32728, 0, 32768, 32773, 33068, 65535, 32767, 32256, 1, 1};
  for (int x = 0; x < 10; ++x)
    EXPECT_EQ(png.at<std::uint16_t>(0, x), want[x]) << x;
  const cv::Mat back = readDisparity16Png(path.string(), inv);
  std::filesystem::remove(path);
  ASSERT_EQ(back.type(), CV_16SC1);
  for (int x = 0; x < 9; ++x)
    EXPECT_EQ(back.at<std::int16_t>(0, x), row[x]) << x;
  EXPECT_EQ(back.at<std::int16_t>(0, 9), -32767) << "-32768 is written as -32767";
  // An 8-bit file is refused with its name.
  const auto eight = tempFile("eight.png");
  ASSERT_TRUE(cv::imwrite(eight.string(), cv::Mat::zeros(2, 2, CV_8U)));
  try {
    readDisparity16Png(eight.string(), inv);
    ADD_FAILURE() << "an 8-bit image was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(eight.string()), std::string::npos) << e.what();
  }
  std::filesystem::remove(eight);
}

// disparity.pfm: float px, inf = invalid, rows bottom to top, little-endian.
TEST(Frontend, DisparityPfmRoundTripsWithInfAsInvalid) {
  const std::int16_t inv = -17 * 16;
  const std::int16_t map[2][3] = {{-40, inv, 0}, {5, 32767, -3}};
  const auto path = tempFile("disparity.pfm");
  writeDisparityPfm(path.string(), {map, 3, 2, sizeof map[0], PixelType::S16C1}, inv);
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string header = "Pf\n3 2\n-1.0\n";
  ASSERT_EQ(bytes.size(), header.size() + 6 * 4);
  EXPECT_EQ(bytes.substr(0, header.size()), header);
  float first = 0;  // the bottom row comes first: 5 / 16
  std::memcpy(&first, bytes.data() + header.size(), 4);
  EXPECT_EQ(first, 5 / 16.0f);
  EXPECT_TRUE(isPfmFile(path.string()));
  const cv::Mat px = readPfm(path.string());
  // OpenCV reads the same file to the same pixels.
  if (cv::haveImageReader(path.string())) {
    const cv::Mat theirs = cv::imread(path.string(), cv::IMREAD_UNCHANGED);
    ASSERT_EQ(theirs.type(), CV_32FC1);
    ASSERT_EQ(theirs.size(), px.size());
    EXPECT_EQ(std::memcmp(theirs.data, px.data, 6 * sizeof(float)), 0);
  }
  std::filesystem::remove(path);
  ASSERT_EQ(px.type(), CV_32FC1);
  ASSERT_EQ(px.size(), cv::Size(3, 2));
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x) {
      if (map[y][x] == inv)
        EXPECT_TRUE(std::isinf(px.at<float>(y, x)) && px.at<float>(y, x) > 0);
      else
        EXPECT_EQ(px.at<float>(y, x), map[y][x] / 16.0f) << x << "," << y;
    }
}

// Big-endian and colour PFM files (other writers) are read too; malformed
// ones are refused with the file's name.
TEST(Frontend, PfmReaderTakesBothByteOrdersAndRefusesBadFiles) {
  const auto path = tempFile("big.pfm");
  {
    std::ofstream out(path, std::ios::binary);
    out << "PF\n2 1\n1.0\n";
    for (float v : {1.5f, 0.f, 0.f, -2.25f, 0.f, 0.f}) {
      std::uint32_t bits = 0;
      std::memcpy(&bits, &v, 4);
      const unsigned char b[4] = {
          static_cast<unsigned char>(bits >> 24), static_cast<unsigned char>(bits >> 16),
          static_cast<unsigned char>(bits >> 8), static_cast<unsigned char>(bits)};
      out.write(reinterpret_cast<const char*>(b), 4);
    }
  }
  const cv::Mat px = readPfm(path.string());
  ASSERT_EQ(px.size(), cv::Size(2, 1));
  EXPECT_EQ(px.at<float>(0, 0), 1.5f);
  EXPECT_EQ(px.at<float>(0, 1), -2.25f);
  for (const std::string& bad : {std::string("P5\n2 1\n255\nab"), std::string("Pf\n2 1\n-1.0\nabc"),
                                 std::string("Pf\n2 x\n-1.0\n12345678"), std::string("Pf\n2")}) {
    std::ofstream(path, std::ios::binary) << bad;
    try {
      readPfm(path.string());
      ADD_FAILURE() << "accepted: " << bad;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    }
  }
  std::filesystem::remove(path);
  EXPECT_THROW(readPfm(path.string()), Error);
}

// Near is hot: the colour view puts more red on larger disparities.
TEST(Frontend, ColourViewGoesFromBlueToRed) {
  StereoParams p;
  p.numDisparities = 64;
  std::int16_t row[3] = {16 * 2, 16 * 60, invalidDisparity(p)};
  const cv::Mat colour = colorizeDisparity({row, 3, 1, sizeof row, PixelType::S16C1}, p);
  const cv::Vec3b far = colour.at<cv::Vec3b>(0, 0), near = colour.at<cv::Vec3b>(0, 1);
  EXPECT_GT(near[2], far[2]) << "red";
  EXPECT_GT(far[0], near[0]) << "blue";
  EXPECT_EQ(colour.at<cv::Vec3b>(0, 2), cv::Vec3b(0, 0, 0)) << "invalid is black";
}

// The colour view is the JET map of the disparity's level in [lo, hi]
// (saturated outside), black where invalid: every 16-bit value, against the
// map applied pixel by pixel.
TEST(Frontend, ColourViewIsTheJetMapOfEachDisparitysLevel) {
  StereoParams p;
  p.minDisparity = 3;
  p.numDisparities = 48;
  cv::Mat disparity(256, 256, CV_16SC1);
  for (int i = 0; i < 65536; ++i)
    disparity.at<std::int16_t>(i / 256, i % 256) = static_cast<std::int16_t>(i - 32768);
  const cv::Mat colour = colorizeDisparity(viewOf(disparity), p);
  const double lo = p.minDisparity * 16.0, hi = (p.minDisparity + p.numDisparities) * 16.0;
  cv::Mat level(disparity.size(), CV_8UC1), expected;
  for (int i = 0; i < 65536; ++i)
    level.at<std::uint8_t>(i / 256, i % 256) = cv::saturate_cast<std::uint8_t>(
        255.0 * (disparity.at<std::int16_t>(i / 256, i % 256) - lo) / (hi - lo));
  cv::applyColorMap(level, expected, cv::COLORMAP_JET);
  expected.setTo(cv::Scalar::all(0), disparity == invalidDisparity(p));
  ASSERT_EQ(colour.size(), expected.size());
  EXPECT_EQ(cv::norm(colour, expected, cv::NORM_INF), 0);
  EXPECT_GT(cv::countNonZero(expected.reshape(1) != 0), 0) << "not all black";
}

// Drawn into a panel of a larger image: the same colours as the view of its
// own, the image around the panel untouched; a panel of another size or
// type is refused.
TEST(Frontend, ColourViewDrawnIntoAPanelMatchesItsOwnImage) {
  StereoParams p;
  p.numDisparities = 32;
  cv::Mat disparity(20, 30, CV_16SC1);
  for (int i = 0; i < 600; ++i)
    disparity.at<std::int16_t>(i / 30, i % 30) =
        i % 7 == 0 ? invalidDisparity(p) : static_cast<std::int16_t>(i - 40);
  cv::Mat mosaic(40, 60, CV_8UC3, cv::Scalar(7, 8, 9));
  cv::Mat panel = mosaic(cv::Rect(25, 10, 30, 20));
  colorizeDisparityInto(viewOf(disparity), p, panel);
  EXPECT_EQ(panel.data, mosaic.ptr(10, 25)) << "drawn in place";
  EXPECT_EQ(cv::norm(panel, colorizeDisparity(viewOf(disparity), p), cv::NORM_INF), 0);
  cv::Mat around = mosaic.clone();
  around(cv::Rect(25, 10, 30, 20)).setTo(cv::Scalar(7, 8, 9));
  EXPECT_EQ(cv::norm(around, cv::Mat(around.size(), CV_8UC3, cv::Scalar(7, 8, 9)), cv::NORM_INF), 0)
      << "the image around the panel untouched";
  cv::Mat small(19, 30, CV_8UC3), grey(20, 30, CV_8UC1);
  EXPECT_THROW(colorizeDisparityInto(viewOf(disparity), p, small), Error);
  EXPECT_THROW(colorizeDisparityInto(viewOf(disparity), p, grey), Error);
}

// The colour scale: blue at its left end (the lowest disparity), red at its
// right end, the rest of the view untouched.
TEST(Frontend, ColourScaleRunsFromBlueToRedInItsCorner) {
  StereoParams p;
  p.numDisparities = 64;
  cv::Mat view(240, 320, CV_8UC3, cv::Scalar(10, 200, 30));
  const cv::Rect area = drawDisparityScale(view, p);
  ASSERT_FALSE(area.empty());
  EXPECT_EQ(area, disparityScaleRect(view.size()));
  EXPECT_EQ(area.br(), cv::Point(view.cols, view.rows)) << "bottom-right corner";
  cv::Mat outside = view.clone();
  outside(area).setTo(cv::Scalar(10, 200, 30));
  const cv::Scalar fill(10, 200, 30);
  EXPECT_EQ(cv::norm(outside, cv::Mat(outside.size(), outside.type(), fill), cv::NORM_INF), 0);
  // The bar's first and last columns, on its middle row (6 px margin, 8 px high).
  const int y = area.y + 6 + 4;
  const cv::Vec3b low = view.at<cv::Vec3b>(y, area.x + 6);
  const cv::Vec3b high = view.at<cv::Vec3b>(y, area.x + area.width - 7);
  EXPECT_GT(low[0], low[2]) << "the low end is blue";
  EXPECT_GT(high[2], high[0]) << "the high end is red";
  // Too small a view gets no scale, and is left as it was.
  cv::Mat tiny(20, 40, CV_8UC3, cv::Scalar(1, 2, 3));
  EXPECT_TRUE(drawDisparityScale(tiny, p).empty());
  EXPECT_EQ(cv::norm(tiny, cv::Mat(tiny.size(), tiny.type(), cv::Scalar(1, 2, 3)), cv::NORM_INF),
            0);
}

}  // namespace
}  // namespace horopter::test
