// Conformance: every kernel of every registered backend against the scalar
// reference (scalarBackend()), bit for bit, on identical inputs.
//
// The fixture is instantiated over registeredBackends(), so a new backend is
// enrolled by registering it. A backend that is not available on this machine
// is skipped with its reason, unless HOROPTER_REQUIRE_BACKENDS (a
// comma-separated list of names) names it: then it fails.
//
// An OpenCL backend is enrolled twice, once per shape of its SAD matcher
// ("opencl@strip", "opencl@tiled": HOROPTER_OPENCL_SAD is set for the case),
// so both shapes meet the reference on every run, whichever one the device
// would pick by itself.
//
// The reference runs on tightly packed buffers; the backend runs on the same
// pixels in three layouts: tight (exact-size allocations, so AddressSanitizer
// catches any access past the last pixel), padded strides, and a view into the
// middle of a larger buffer (non-zero ROI origin). Every byte around the view
// holds a canary that must survive, and inputs must come back unchanged.
#include <algorithm>
#include <array>
#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "common/kernel_table.hpp"
#include "horopter/kernels/backend.hpp"
#include "horopter/kernels/kernels.hpp"
#include "horopter/vision/frontend.hpp"
#include "horopter/vision/geometry.hpp"
#include "horopter/vision/opencv.hpp"
#include "horopter/vision/zone_search.hpp"
#include "sad/sad.hpp"
#include "scoped_env.hpp"
#include "test_support.hpp"

namespace horopter::test {
namespace {

std::vector<std::string> registeredNames() {
  std::vector<std::string> names;
  for (const Backend* b : registeredBackends())
    names.push_back(b->name);
  return names;
}

std::vector<std::string> requiredNames() {
  std::vector<std::string> names;
  const char* env = std::getenv("HOROPTER_REQUIRE_BACKENDS");
  if (env == nullptr) return names;
  std::stringstream list(env);
  for (std::string name; std::getline(list, name, ',');) {
    name.erase(0, name.find_first_not_of(" \t"));
    name.erase(name.find_last_not_of(" \t") + 1);
    if (!name.empty()) names.push_back(name);
  }
  return names;
}

// The fixture's parameters: a backend's name, with "@strip" or "@tiled"
// (the SAD matcher's shape) for an OpenCL backend.
std::vector<std::string> conformanceParams() {
  std::vector<std::string> params;
  for (const std::string& name : registeredNames()) {
    if (name.rfind("opencl", 0) == 0) {
      params.push_back(name + "@strip");
      params.push_back(name + "@tiled");
    } else {
      params.push_back(name);
    }
  }
  return params;
}
std::string backendOf(const std::string& param) {
  return param.substr(0, param.find('@'));
}
std::string sadShapeOf(const std::string& param) {
  const std::size_t at = param.find('@');
  return at == std::string::npos ? "" : param.substr(at + 1);
}

const Backend* backendNamed(const std::string& name) {
  for (const Backend* b : registeredBackends())
    if (b->name == name) return b;
  return nullptr;
}

TEST(ConformanceSetup, ScalarReferenceIsRegisteredAndAvailable) {
  const Backend* scalar = backendNamed("scalar");
  ASSERT_NE(scalar, nullptr);
  EXPECT_EQ(scalar, &scalarBackend());
  EXPECT_TRUE(scalar->available);
  ASSERT_TRUE(scalar->kernels);
  const KernelTable& k = *scalar->kernels;
  EXPECT_TRUE(k.prefilterXSobel && k.prefilterNormalized && k.matchBlocks && k.leftRightCheck &&
              k.filterSpeckles && k.medianFilter && k.horopterMask);
}

TEST(ConformanceSetup, BackendNamesAreUniqueAndDescribed) {
  const auto names = registeredNames();
  for (std::size_t i = 0; i < names.size(); ++i) {
    EXPECT_FALSE(names[i].empty());
    for (std::size_t j = i + 1; j < names.size(); ++j)
      EXPECT_NE(names[i], names[j]) << "two backends share a name";
  }
  for (const Backend* b : registeredBackends()) {
    EXPECT_FALSE(b->description.empty()) << b->name;
    if (!b->available) {
      EXPECT_FALSE(b->unavailableReason.empty()) << b->name << " says no reason";
    }
  }
}

// A backend demanded by HOROPTER_REQUIRE_BACKENDS must at least be built in.
TEST(ConformanceSetup, RequiredBackendsAreRegistered) {
  for (const std::string& name : requiredNames())
    EXPECT_NE(backendNamed(name), nullptr)
        << "HOROPTER_REQUIRE_BACKENDS names '" << name << "', which this build does not register";
}

class Conformance : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    const std::string name = backendOf(GetParam());
    backend_ = backendNamed(name);
    ASSERT_NE(backend_, nullptr) << GetParam();
    if (const std::string shape = sadShapeOf(GetParam()); !shape.empty())
      sadShape_.emplace("HOROPTER_OPENCL_SAD", shape.c_str());
    if (!backend_->available) {
      const auto required = requiredNames();
      if (std::find(required.begin(), required.end(), name) != required.end())
        FAIL() << "backend '" << name
               << "' is required (HOROPTER_REQUIRE_BACKENDS) but not available here: "
               << backend_->unavailableReason;
      GTEST_SKIP() << "backend '" << name
                   << "' is not available on this machine: " << backend_->unavailableReason
                   << " (list it in HOROPTER_REQUIRE_BACKENDS to make this a failure)";
    }
  }
  const Backend& backend() const { return *backend_; }
  static const Backend& reference() { return scalarBackend(); }

 private:
  const Backend* backend_ = nullptr;
  std::optional<ScopedEnv> sadShape_;  // HOROPTER_OPENCL_SAD for this case
};

std::string backendTestName(const ::testing::TestParamInfo<std::string>& info) {
  std::string name = info.param;
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(Backends, Conformance, ::testing::ValuesIn(conformanceParams()),
                         backendTestName);

// ---------------------------------------------------------------------------
// Inputs

enum class Pattern { Random, Flat, Saturated, Stripes, Textured };
const char* patternName(Pattern p) {
  switch (p) {
    case Pattern::Random:
      return "random";
    case Pattern::Flat:
      return "flat";
    case Pattern::Saturated:
      return "saturated 0/255";
    case Pattern::Stripes:
      return "vertical stripes";
    case Pattern::Textured:
      return "noisy shifted texture";
  }
  return "?";
}
constexpr Pattern kPatterns[] = {Pattern::Random, Pattern::Flat, Pattern::Saturated,
                                 Pattern::Stripes, Pattern::Textured};

// A pattern image of width w + 2 margin, from which both views of a pair are cut.
TestImage wideImage(int w, int h, Pattern pattern, std::uint64_t seed) {
  TestImage img(w, h, PixelType::U8C1);
  Rng rng(seed);
  const int flat = rng.uniform(0, 255);
  const int period = rng.uniform(2, 7);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      int v = 0;
      switch (pattern) {
        case Pattern::Random:
        case Pattern::Textured:
          v = rng.uniform(0, 255);
          break;
        case Pattern::Flat:
          v = flat;
          break;
        case Pattern::Saturated:
          v = rng.chance(50) ? 255 : 0;
          break;
        case Pattern::Stripes:
          v = (x / period) % 2 ? 255 : 0;
          break;
      }
      img.at<std::uint8_t>(x, y) = static_cast<std::uint8_t>(v);
    }
  }
  return img;
}

TestImage patternImage(int w, int h, Pattern pattern, std::uint64_t seed) {
  return wideImage(w, h, pattern, seed);
}

// left = columns [m, m + w) of a wide pattern, right = columns [m + shift, ...):
// a plane at disparity `shift`. Random: two unrelated images.
StereoPair patternPair(int w, int h, Pattern pattern, int shift, std::uint64_t seed) {
  const int margin = std::abs(shift) + 1;
  const TestImage wide = wideImage(w + 2 * margin, h, pattern, seed);
  StereoPair pair{TestImage(w, h, PixelType::U8C1), TestImage(w, h, PixelType::U8C1)};
  Rng rng(seed + 1);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      pair.left.at<std::uint8_t>(x, y) = wide.at<std::uint8_t>(x + margin, y);
      int r = wide.at<std::uint8_t>(x + margin + shift, y);
      if (pattern == Pattern::Textured) r = std::clamp(r + rng.uniform(-10, 10), 0, 255);
      if (pattern == Pattern::Random) r = rng.uniform(0, 255);
      pair.right.at<std::uint8_t>(x, y) = static_cast<std::uint8_t>(r);
    }
  }
  return pair;
}

std::string describe(const StereoParams& p) {
  std::ostringstream o;
  o << "minDisparity " << p.minDisparity << ", numDisparities " << p.numDisparities
    << ", blockSize " << p.blockSize << ", textureThreshold " << p.textureThreshold
    << ", uniquenessRatio " << p.uniquenessRatio << ", disp12MaxDiff " << p.disp12MaxDiff
    << ", speckleWindowSize " << p.speckleWindowSize << ", speckleRange " << p.speckleRange
    << ", preFilter " << toString(p.preFilterType) << ", size " << p.preFilterSize << ", cap "
    << p.preFilterCap << ", leftBand " << p.leftBand;
  return o.str();
}

// An input must come back unchanged, canaries included.
::testing::AssertionResult untouched(const TestImage& original, const TestImage& passed,
                                     const char* what) {
  const ::testing::AssertionResult same = sameImage(original.view(), passed.view());
  if (!same) return ::testing::AssertionFailure() << what << " was modified: " << same.message();
  const ::testing::AssertionResult canaries = passed.canariesIntact();
  if (!canaries) return ::testing::AssertionFailure() << what << ": " << canaries.message();
  return ::testing::AssertionSuccess();
}

// Each check stops at the first difference (one failure per kernel and
// backend, with the case in the trace), so that the self-tests below can
// expect exactly one failure.
#define CONFORM(result, what)                                    \
  do {                                                           \
    const ::testing::AssertionResult conformResult_ = (result);  \
    if (!conformResult_) {                                       \
      ADD_FAILURE() << what << ": " << conformResult_.message(); \
      return;                                                    \
    }                                                            \
  } while (0)

// ---------------------------------------------------------------------------
// Prefilter

void conformPrefilterXSobel(const Backend& backend) {
  const int widths[] = {1, 2, 3, 31, 32, 33, 63, 64, 65, 641};
  const int heights[] = {1, 2, 3, 4, 9};
  const int caps[] = {1, 31, 63, 17};
  int n = 0;
  for (int w : widths) {
    for (int h : heights) {
      for (Pattern pattern : kPatterns) {
        const int cap = caps[n % 4];
        const std::uint64_t seed = static_cast<std::uint64_t>(++n);
        SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h) + " " + patternName(pattern) +
                     ", cap " + std::to_string(cap));
        const TestImage src = patternImage(w, h, pattern, seed);
        TestImage refFiltered(w, h, PixelType::U8C1), refTexture(w, h, PixelType::U8C1);
        prefilterXSobel(src.view(), cap, refFiltered.view(), refTexture.view(), scalarBackend());
        for (const Layout& layout : kLayouts) {
          for (int outputs = 0; outputs < 3; ++outputs) {  // both, filtered only, texture only
            SCOPED_TRACE(std::string("layout ") + layout.name + ", outputs " +
                         std::to_string(outputs));
            const TestImage in = src.clone(layout);
            TestImage filtered(w, h, PixelType::U8C1, layout),
                texture(w, h, PixelType::U8C1, layout);
            filtered.fillBytes(0xEE);
            texture.fillBytes(0xEE);
            prefilterXSobel(in.view(), cap, outputs != 2 ? filtered.view() : ImageView{},
                            outputs != 1 ? texture.view() : ImageView{}, backend);
            if (outputs != 2) {
              CONFORM(sameImage(refFiltered.view(), filtered.view()), "filtered output");
            }
            if (outputs != 1) {
              CONFORM(sameImage(refTexture.view(), texture.view()), "texture output");
            }
            CONFORM(filtered.canariesIntact(), "filtered output");
            CONFORM(texture.canariesIntact(), "texture output");
            CONFORM(untouched(src, in, "prefilter input"), "prefilter input");
          }
        }
      }
    }
  }
}

// The normalized-response prefilter: sizes around the vector steps (16
// pixels in AVX2) and the window, every window size class (OpenCV's default 9,
// small 5, 21, and 255, wider than every image here so that the window's
// border replication dominates), every cap class, both outputs alone and
// together, and row stripes (the first row of a stripe sums its own window).
void conformPrefilterNormalized(const Backend& backend) {
  const int widths[] = {1, 2, 3, 17, 18, 19, 33, 64, 65, 200};
  const int heights[] = {1, 2, 3, 9, 24};
  const int sizes[] = {5, 9, 21, 255};
  const int caps[] = {1, 31, 63, 17};
  int n = 0;
  for (int w : widths) {
    for (int h : heights) {
      for (Pattern pattern : kPatterns) {
        const int cap = caps[n % 4];
        const int size = sizes[(n / 4) % 4];
        const std::uint64_t seed = static_cast<std::uint64_t>(++n) + 500;
        SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h) + " " + patternName(pattern) +
                     ", cap " + std::to_string(cap) + ", size " + std::to_string(size));
        const TestImage src = patternImage(w, h, pattern, seed);
        TestImage refFiltered(w, h, PixelType::U8C1), refTexture(w, h, PixelType::U8C1);
        prefilterNormalized(src.view(), cap, size, refFiltered.view(), refTexture.view(),
                            scalarBackend());
        for (const Layout& layout : kLayouts) {
          for (int outputs = 0; outputs < 4; ++outputs) {
            // both, filtered only, texture only, both in three row stripes
            SCOPED_TRACE(std::string("layout ") + layout.name + ", outputs " +
                         std::to_string(outputs));
            const TestImage in = src.clone(layout);
            TestImage filtered(w, h, PixelType::U8C1, layout),
                texture(w, h, PixelType::U8C1, layout);
            filtered.fillBytes(0xEE);
            texture.fillBytes(0xEE);
            const ImageView f = outputs != 2 ? filtered.view() : ImageView{};
            const ImageView t = outputs != 1 ? texture.view() : ImageView{};
            if (outputs == 3) {
              for (int i = 0; i < 3; ++i)
                prefilterNormalized(in.view(), cap, size, f, t, backend,
                                    RowRange{h * i / 3, h * (i + 1) / 3});
            } else {
              prefilterNormalized(in.view(), cap, size, f, t, backend);
            }
            if (outputs != 2) {
              CONFORM(sameImage(refFiltered.view(), filtered.view()), "filtered output");
            }
            if (outputs != 1) {
              CONFORM(sameImage(refTexture.view(), texture.view()), "texture output");
            }
            CONFORM(filtered.canariesIntact(), "filtered output");
            CONFORM(texture.canariesIntact(), "texture output");
            CONFORM(untouched(src, in, "prefilter input"), "prefilter input");
          }
        }
      }
    }
  }
}

// ---------------------------------------------------------------------------
// Matching

struct MatchCase {
  int w, h;
  StereoParams p;
  Pattern pattern;
  int shift;
  bool prefiltered;  // match the x-Sobel outputs rather than raw intensities
};

std::vector<MatchCase> matchCases() {
  std::vector<MatchCase> cases;
  int n = 0;
  // Odd and even widths around vector sizes, heights around the window.
  for (int w : {31, 32, 33, 63, 64, 65}) {
    for (int blockSize : {3, 5, 9}) {
      for (Pattern pattern : kPatterns) {
        StereoParams p;
        p.blockSize = blockSize;
        p.numDisparities = 16;
        p.minDisparity = (n % 3 == 0) ? 0 : (n % 3 == 1 ? -8 : 4);
        p.textureThreshold = (n % 4 == 0) ? 0 : 10;
        p.uniquenessRatio = (n % 5 == 0) ? 0 : 15;
        const int h = blockSize + (n % 4 == 3 ? 5 : n % 4);
        const int shift = p.minDisparity + (n * 7) % 16;
        cases.push_back({w, h, p, pattern, shift, n % 2 == 0});
        ++n;
      }
    }
  }
  // Parameter sweeps on one size.
  for (int blockSize : {3, 5, 7, 9, 11, 15, 21}) {
    for (int numD : {16, 32}) {
      for (int uniqueness : {0, 5, 15, 50, 1000}) {  // 1000: limits past every cost
        StereoParams p;
        p.blockSize = blockSize;
        p.numDisparities = numD;
        p.minDisparity = (n % 4 == 0) ? 0 : (n % 4 == 1 ? -3 : (n % 4 == 2 ? -8 : 5));
        p.textureThreshold = (n % 3 == 0) ? 0 : (n % 3 == 1 ? 10 : 100);
        p.uniquenessRatio = uniqueness;
        const int shift = p.minDisparity + (n * 5) % numD;
        cases.push_back({80, blockSize + 6, p, kPatterns[n % 5], shift, n % 3 != 0});
        ++n;
      }
    }
  }
  // All-negative and all-positive ranges, and the widest image.
  {
    StereoParams p;
    p.minDisparity = -40;
    p.numDisparities = 16;
    p.blockSize = 5;
    cases.push_back({90, 12, p, Pattern::Textured, -30, true});
    p.minDisparity = 20;
    cases.push_back({90, 12, p, Pattern::Textured, 27, true});
    StereoParams big;  // defaults: 64 disparities, block 9
    cases.push_back({641, 13, big, Pattern::Textured, 37, true});
    big.blockSize = 7;
    big.numDisparities = 16;
    cases.push_back({641, 7, big, Pattern::Stripes, 5, false});  // a single region row
  }
  // Wide ranges (several 16-disparity groups, not powers of two), a negative
  // range across zero, and large blocks on both sides of the 16-bit cost
  // bound that vector code may use (raw saturated input: |diff| up to 255).
  {
    int k = 0;
    for (int numD : {48, 80, 128, 256}) {
      StereoParams p;
      p.numDisparities = numD;
      p.blockSize = 9;
      p.minDisparity = (k % 2 == 0) ? 0 : -numD / 2;
      const int shift = p.minDisparity + numD / 3;
      cases.push_back({numD + 60 + k, 14, p, kPatterns[k % 5], shift, k % 2 == 0});
      ++k;
    }
    // HD widths at 128 disparities and block 15 (the 1280x720 target): rows
    // of costs padded to an odd number of cache lines, nine tiles per row
    // pass with a partial last one, both signs of the range's start.
    for (int w : {1280, 1281, 1296, 1311, 1327}) {
      StereoParams p;
      p.numDisparities = 128;
      p.blockSize = 15;
      p.minDisparity = (k % 2 == 0) ? 0 : -20;
      p.textureThreshold = (k % 3 == 0) ? 0 : 10;
      const int shift = p.minDisparity + 37 + k;
      cases.push_back({w, 15 + k % 4, p, kPatterns[k % 5], shift, k % 4 != 3});
      ++k;
    }
    // Every count of region pixels modulo 16 with one pair of 16-disparity
    // groups: the AVX2 sweep stores a pair's costs in half blocks of 8
    // pixels, the last one padded with "no cost". Region pixels are
    // w - 2r - (numDisparities - 1) = 48 + extra here, for both ranges.
    for (int extra = 0; extra < 16; ++extra) {
      StereoParams p;
      p.numDisparities = 32;
      p.blockSize = 7;
      p.minDisparity = (extra % 2 == 0) ? 0 : -5;
      p.uniquenessRatio = (extra % 3 == 0) ? 0 : 15;
      p.textureThreshold = (extra % 4 == 0) ? 0 : 10;
      const int w = 2 * (p.blockSize / 2) + (p.numDisparities - 1) + 48 + extra;
      EXPECT_EQ(matchRegion(w, 10, p).x1 - matchRegion(w, 10, p).x0, 48 + extra);
      cases.push_back(
          {w, 10 + extra % 3, p, kPatterns[extra % 5], p.minDisparity + 11, extra % 2 == 0});
    }
    for (int blockSize : {15, 17, 25, 33, 51}) {
      for (Pattern pattern : {Pattern::Saturated, Pattern::Textured}) {
        for (bool prefiltered : {false, true}) {
          StereoParams p;
          p.numDisparities = 16;
          p.blockSize = blockSize;
          p.minDisparity = -4;
          p.textureThreshold = prefiltered ? 10 : 0;
          cases.push_back({blockSize + 40, blockSize + 3, p, pattern, 3, prefiltered});
        }
      }
    }
  }
  return cases;
}

// The matcher's inputs from a pattern pair: with `prefiltered`, the pair
// becomes its x-Sobel prefiltered views (as the front end feeds them);
// either way the left view's texture image is returned.
TestImage prefilterForMatching(StereoPair& pair, int cap, bool prefiltered) {
  const int w = pair.left.view().width, h = pair.left.view().height;
  TestImage texture(w, h, PixelType::U8C1);
  if (prefiltered) {
    TestImage lf(w, h, PixelType::U8C1), rf(w, h, PixelType::U8C1);
    prefilterXSobel(pair.left.view(), cap, lf.view(), texture.view(), scalarBackend());
    prefilterXSobel(pair.right.view(), cap, rf.view(), {}, scalarBackend());
    pair = {std::move(lf), std::move(rf)};
  } else {
    prefilterXSobel(pair.left.view(), cap, {}, texture.view(), scalarBackend());
  }
  return texture;
}

void conformMatchBlocks(const Backend& backend) {
  for (const MatchCase& c : matchCases()) {
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      const int w = c.w, h = c.h;
      SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h) + " " + patternName(c.pattern) +
                   ", shift " + std::to_string(c.shift) +
                   (c.prefiltered ? ", prefiltered" : ", raw") + ", seed " + std::to_string(seed) +
                   ", " + describe(c.p));
      ASSERT_FALSE(matchRegion(w, h, c.p).empty());
      StereoPair pair = patternPair(w, h, c.pattern, c.shift,
                                    seed * 7777 + static_cast<std::uint64_t>(w * 31 + h + c.shift));
      const TestImage texture = prefilterForMatching(pair, c.p.preFilterCap, c.prefiltered);
      TestImage refDisparity(w, h, PixelType::S16C1), refWinner(w, h, PixelType::S16C1);
      matchBlocks(pair.left.view(), pair.right.view(), texture.view(), c.p, refDisparity.view(),
                  refWinner.view(), scalarBackend());
      for (const Layout& layout : kLayouts) {
        SCOPED_TRACE(std::string("layout ") + layout.name);
        const TestImage left = pair.left.clone(layout), right = pair.right.clone(layout);
        const TestImage tex = texture.clone(layout);
        TestImage disparity(w, h, PixelType::S16C1, layout), winner(w, h, PixelType::S16C1, layout);
        disparity.fillBytes(0x77);
        winner.fillBytes(0x77);
        matchBlocks(left.view(), right.view(), tex.view(), c.p, disparity.view(), winner.view(),
                    backend);
        CONFORM(sameImage(refDisparity.view(), disparity.view()), "disparity");
        CONFORM(sameImage(refWinner.view(), winner.view()), "winnerRight");
        CONFORM(disparity.canariesIntact(), "disparity");
        CONFORM(winner.canariesIntact(), "winnerRight");
        CONFORM(untouched(pair.left, left, "left"), "left");
        CONFORM(untouched(pair.right, right, "right"), "right");
        CONFORM(untouched(texture, tex, "texture"), "texture");
      }
    }
  }
}

// How many pixels of two same-sized S16C1 images differ.
long long differingPixels(const TestImage& a, const TestImage& b) {
  long long n = 0;
  for (int y = 0; y < a.view().height; ++y)
    for (int x = 0; x < a.view().width; ++x)
      n += a.view().row<std::int16_t>(y)[x] != b.view().row<std::int16_t>(y)[x];
  return n;
}

// The backend's matchBlocks with `guard`, in every layout and in two
// stripes of rows (as the front end's threads call it), against the
// reference's maps; the inputs must come back untouched.
void conformStripedMatch(const Backend& backend, const StereoPair& pair, const TestImage& texture,
                         const StereoParams& p, const BelowRangeGuard& guard,
                         const TestImage& refDisparity, const TestImage& refWinner) {
  const int w = pair.left.view().width, h = pair.left.view().height;
  for (const Layout& layout : kLayouts) {
    SCOPED_TRACE(std::string("layout ") + layout.name);
    const TestImage left = pair.left.clone(layout), right = pair.right.clone(layout);
    const TestImage tex = texture.clone(layout);
    TestImage disparity(w, h, PixelType::S16C1, layout), winner(w, h, PixelType::S16C1, layout);
    disparity.fillBytes(0x77);
    winner.fillBytes(0x77);
    for (const RowRange rows : {RowRange{0, h / 3}, RowRange{h / 3, h}})
      matchBlocks(left.view(), right.view(), tex.view(), p, guard, disparity.view(), winner.view(),
                  backend, rows);
    CONFORM(sameImage(refDisparity.view(), disparity.view()), "disparity");
    CONFORM(sameImage(refWinner.view(), winner.view()), "winnerRight");
    CONFORM(disparity.canariesIntact(), "disparity");
    CONFORM(winner.canariesIntact(), "winnerRight");
    CONFORM(untouched(pair.left, left, "left"), "left");
    CONFORM(untouched(pair.right, right, "right"), "right");
  }
}

// A matching case with the guard below the range (step 0: off).
struct GuardedMatchCase {
  int w, h;
  StereoParams p;
  BelowRangeGuard guard;
  Pattern pattern;
  int shift;
  bool prefiltered;
};

// Matching with the guard below the range (zone-limited matching): steps
// from 1 up to past the gap, uniqueness on and off, texture on and off,
// raw and prefiltered inputs, checked disparities below zero (whose windows
// leave the right image near its right edge), blocks past the AVX2 16-bit
// bound (its scalar fallback), and stripes of rows. The scenes put the
// true match below the range, so that the guard has pixels to remove: the
// sweep also asserts that it removed some.
void conformMatchBlocksGuarded(const Backend& backend) {
  std::vector<GuardedMatchCase> cases;
  int k = 0;
  for (int step : {1, 2, 3, 5, 40}) {
    for (int ratio : {0, 15, 100}) {
      StereoParams p;
      p.minDisparity = 16 + k % 3;
      p.numDisparities = (k % 2 == 0) ? 48 : 16;
      p.blockSize = (k % 3 == 0) ? 5 : 9;
      p.uniquenessRatio = ratio;
      p.textureThreshold = (k % 4 == 0) ? 0 : 10;
      cases.push_back({97 + 13 * (k % 5),
                       23 + k % 3,
                       p,
                       {step, k % 2 == 0 ? 0 : 7},
                       kPatterns[k % 5],
                       11 + k % 4,
                       k % 3 != 2});
      ++k;
    }
  }
  for (int step : {1, 4, 7}) {  // checked disparities below zero
    StereoParams p;
    p.minDisparity = 8;
    p.numDisparities = 16;
    p.blockSize = 7;
    cases.push_back({83, 19, p, {step, -20}, Pattern::Textured, -6, true});
  }
  // Steps 1 and 2 (the AVX2 matcher sweeps the checked disparities' span
  // as 16-lane groups below the range's): every checked disparity below
  // zero and below a negative range, whose windows reach past the right
  // image at the region's right end; and many groups (8 or 15, the last
  // partial) with the true disparity among them.
  for (int step : {1, 2}) {
    for (int ratio : {0, 15}) {
      StereoParams p;
      p.minDisparity = -5;
      p.numDisparities = 32;
      p.blockSize = 5;
      p.uniquenessRatio = ratio;
      cases.push_back({90, 17, p, {step, -30}, Pattern::Textured, -12 - step, ratio == 0});
      p.minDisparity = 120;
      p.blockSize = 7;
      cases.push_back({200, 15, p, {step, 3}, Pattern::Textured, 60, ratio != 0});
    }
  }
  // 17, 33: past the AVX2 bound (its scalar fallback); 231: past the block
  // (225) up to which the tiled OpenCL matcher costs 4 planes per pass.
  for (int blockSize : {17, 33, 231}) {
    StereoParams p;
    p.minDisparity = 10;
    p.numDisparities = 16;
    p.blockSize = blockSize;
    p.textureThreshold = 0;
    cases.push_back({blockSize + 60, blockSize + 5, p, {2, 0}, Pattern::Textured, 6, false});
  }
  {
    StereoParams p;  // nothing below to check
    p.minDisparity = 4;
    p.numDisparities = 16;
    cases.push_back({61, 17, p, {3, 4}, Pattern::Random, 2, true});
  }
  long long removed = 0, rightChanged = 0;
  for (const GuardedMatchCase& c : cases) {
    const int w = c.w, h = c.h;
    SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h) + " " + patternName(c.pattern) +
                 ", shift " + std::to_string(c.shift) + ", guard step " +
                 std::to_string(c.guard.step) + " down to " + std::to_string(c.guard.lowest) +
                 (c.prefiltered ? ", prefiltered" : ", raw") + ", " + describe(c.p));
    StereoPair pair = patternPair(w, h, c.pattern, c.shift,
                                  static_cast<std::uint64_t>(w * 31 + h + c.shift + c.guard.step));
    const TestImage texture = prefilterForMatching(pair, c.p.preFilterCap, c.prefiltered);
    TestImage refDisparity(w, h, PixelType::S16C1), refWinner(w, h, PixelType::S16C1);
    matchBlocks(pair.left.view(), pair.right.view(), texture.view(), c.p, c.guard,
                refDisparity.view(), refWinner.view(), scalarBackend());
    TestImage plain(w, h, PixelType::S16C1), plainWinner(w, h, PixelType::S16C1);
    matchBlocks(pair.left.view(), pair.right.view(), texture.view(), c.p, plain.view(),
                plainWinner.view(), scalarBackend());
    removed += differingPixels(plain, refDisparity);
    rightChanged += differingPixels(plainWinner, refWinner);
    conformStripedMatch(backend, pair, texture, c.p, c.guard, refDisparity, refWinner);
  }
  EXPECT_GT(removed, 0) << "the guard removed no pixel in any case: the sweep tests nothing";
  EXPECT_GT(rightChanged, 0) << "the guard changed no right winner: the sweep tests nothing";
}

// Matching with the left band (StereoParams::leftBand): band widths from
// one disparity to the whole range, image widths at and just above the
// smallest the region allows and the front end's (640 at 64 disparities,
// 1280 at 128 and block 15), ranges below, across and above zero, the
// guard below the range with the band, a block past the AVX2 16-bit bound
// (its scalar fallback), uniqueness and texture on and off, raw and
// prefiltered inputs, and stripes of rows. The band must have made some
// pixels valid and changed some right winners, or the sweep tests nothing.
void conformMatchBlocksLeftBand(const Backend& backend) {
  std::vector<GuardedMatchCase> cases;
  int k = 0;
  const auto add = [&](int w, int h, StereoParams p, BelowRangeGuard guard, int shift) {
    p.uniquenessRatio = std::array{15, 0, 100}[k % 3];
    p.textureThreshold = (k % 4 == 3) ? 0 : 10;
    cases.push_back({w, h, p, guard, kPatterns[k % 5], shift, k % 2 == 0});
    ++k;
  };
  for (int band : {1, 2, 16, 63, 64}) {
    StereoParams p;
    p.numDisparities = 64;
    p.blockSize = 9;
    p.leftBand = band;
    const int needed = p.blockSize + p.numDisparities - 1;
    for (int w : {needed, needed + 1, needed + 17, 640})
      add(w, 13 + k % 3, p, {}, 3 + k % 9);
  }
  for (int minD : {-10, 7}) {
    for (int band : {1, 5, 32}) {
      StereoParams p;
      p.minDisparity = minD;
      p.numDisparities = 32;
      p.blockSize = (band % 2 == 0) ? 7 : 5;
      p.leftBand = band;
      add(97 + k, 17, p, {}, minD + 2 + k % 5);
    }
  }
  {
    StereoParams p;  // the HD target
    p.numDisparities = 128;
    p.blockSize = 15;
    p.leftBand = 16;
    add(1280, 18, p, {}, 9);
    add(1287, 17, p, {}, 30);
  }
  for (int step : {1, 3}) {  // the guard below the range, with the band
    StereoParams p;
    p.minDisparity = 16;
    p.numDisparities = 48;
    p.blockSize = 7;
    p.leftBand = 8;
    add(150, 19, p, {step, step == 1 ? 0 : 5}, 9);
    add(150, 19, p, {step, 0}, 24);
  }
  {
    StereoParams p;  // past the AVX2 16-bit cost bound: its scalar fallback
    p.numDisparities = 16;
    p.blockSize = 17;
    p.leftBand = 4;
    add(80, 22, p, {}, 5);
  }
  for (int w : {25, 26, 27}) {
    // The guard below zero at the smallest widths: the right winners the band
    // rewrites (up to x0 - the lowest checked disparity) reach past the
    // costed columns, which x1 clips; a backend's scratch must not carry
    // over from the row before.
    StereoParams p;
    p.numDisparities = 16;
    p.blockSize = 9;
    p.leftBand = 2;
    add(w, 14, p, {2, -10}, 3);
  }
  long long bandValid = 0, rightChanged = 0;
  for (const GuardedMatchCase& c : cases) {
    const int w = c.w, h = c.h;
    SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h) + " " + patternName(c.pattern) +
                 ", shift " + std::to_string(c.shift) + ", guard step " +
                 std::to_string(c.guard.step) + " down to " + std::to_string(c.guard.lowest) +
                 (c.prefiltered ? ", prefiltered" : ", raw") + ", " + describe(c.p));
    ASSERT_FALSE(matchRegion(w, h, c.p).empty());
    StereoPair pair = patternPair(w, h, c.pattern, c.shift,
                                  static_cast<std::uint64_t>(w * 37 + h + c.shift + c.p.leftBand));
    const TestImage texture = prefilterForMatching(pair, c.p.preFilterCap, c.prefiltered);
    TestImage refDisparity(w, h, PixelType::S16C1), refWinner(w, h, PixelType::S16C1);
    matchBlocks(pair.left.view(), pair.right.view(), texture.view(), c.p, c.guard,
                refDisparity.view(), refWinner.view(), scalarBackend());
    StereoParams noBand = c.p;
    noBand.leftBand = 0;
    TestImage plain(w, h, PixelType::S16C1), plainWinner(w, h, PixelType::S16C1);
    matchBlocks(pair.left.view(), pair.right.view(), texture.view(), noBand, c.guard, plain.view(),
                plainWinner.view(), scalarBackend());
    bandValid += differingPixels(plain, refDisparity);
    rightChanged += differingPixels(plainWinner, refWinner);
    conformStripedMatch(backend, pair, texture, c.p, c.guard, refDisparity, refWinner);
  }
  EXPECT_GT(bandValid, 0) << "the band changed no pixel in any case: the sweep tests nothing";
  EXPECT_GT(rightChanged, 0) << "the band changed no right winner: the sweep tests nothing";
}

// ---------------------------------------------------------------------------
// Left-right check

// Surfaces: disparities that drift by a pixel or so along a row, with steps
// of up to `step` px, invalid pixels, and values near both int16 ends where
// `extremes` (the AVX2 check looks up 32 right pixels at a time where the
// row is this smooth, and gathers elsewhere).
TestImage surfaceDisparityMap(int width, int height, const StereoParams& p, std::uint64_t seed,
                              int step, bool extremes) {
  TestImage map(width, height, PixelType::S16C1);
  Rng rng(seed);
  const std::int16_t invalid = invalidDisparity(p);
  for (int y = 0; y < height; ++y) {
    int v = rng.uniform(p.minDisparity, p.minDisparity + p.numDisparities - 1) * kDisparityScale;
    for (int x = 0; x < width; ++x) {
      if (rng.chance(3)) v += rng.uniform(-step, step) * kDisparityScale;
      v += rng.uniform(-12, 12);
      v = std::clamp(v, -32768, 32767);
      std::int16_t value = static_cast<std::int16_t>(v);
      if (rng.chance(5)) value = invalid;
      if (extremes && rng.chance(2))
        value = static_cast<std::int16_t>(rng.chance(50) ? 32767 - rng.uniform(0, 8)
                                                         : -32768 + rng.uniform(0, 8));
      map.at<std::int16_t>(x, y) = value;
    }
  }
  return map;
}

void conformLeftRightCheck(const Backend& backend) {
  int n = 0;
  for (int minD : {0, -8, 4}) {
    for (int maxDiff : {-1, 0, 1, 2, 7, 2047}) {
      // Random maps, matcher output, surfaces (near the int16 ends too).
      for (int source = 0; source < 4; ++source) {
        for (int w : {17, 31, 32, 33, 64, 65, 200}) {
          ++n;
          StereoParams p;
          p.minDisparity = minD;
          p.numDisparities = 16;
          p.blockSize = 5;
          p.textureThreshold = 0;
          p.disp12MaxDiff = maxDiff;
          const int h = 9;
          TestImage d, wr;
          if (source == 0) {
            d = randomDisparityMap(w, h, p, static_cast<std::uint64_t>(n), 20);
            wr = randomImage(w, h, PixelType::S16C1, static_cast<std::uint64_t>(n + 500), minD - 1,
                             minD + 15);
          } else if (source >= 2) {
            const bool extremes = source == 3;
            d = surfaceDisparityMap(w, h, p, static_cast<std::uint64_t>(n), 20, extremes);
            wr = extremes ? randomImage(w, h, PixelType::S16C1, static_cast<std::uint64_t>(n + 500),
                                        -32768, 32767)
                          : randomImage(w, h, PixelType::S16C1, static_cast<std::uint64_t>(n + 500),
                                        minD - 1, minD + 15);
          } else {
            if (w < 5 + 15 + std::max(minD, 0) - std::min(minD, 0)) continue;
            const StereoPair pair =
                patternPair(w, h, Pattern::Textured, minD + 6, static_cast<std::uint64_t>(n));
            d = TestImage(w, h, PixelType::S16C1);
            wr = TestImage(w, h, PixelType::S16C1);
            matchBlocks(pair.left.view(), pair.right.view(), {}, p, d.view(), wr.view(),
                        scalarBackend());
          }
          const char* const sources[] = {" random", " matched", " surface", " surface, extremes"};
          SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h) + sources[source] + ", " +
                       describe(p));
          TestImage ref = d.clone();
          leftRightCheck(ref.view(), wr.view(), p, scalarBackend());
          for (const Layout& layout : kLayouts) {
            SCOPED_TRACE(std::string("layout ") + layout.name);
            TestImage out = d.clone(layout);
            const TestImage winners = wr.clone(layout);
            leftRightCheck(out.view(), winners.view(), p, backend);
            CONFORM(sameImage(ref.view(), out.view()), "disparity");
            CONFORM(out.canariesIntact(), "disparity");
            CONFORM(untouched(wr, winners, "winnerRight"), "winnerRight");
          }
        }
      }
    }
  }
}

// ---------------------------------------------------------------------------
// Speckles

void conformFilterSpeckles(const Backend& backend) {
  const std::pair<int, int> sizes[] = {{1, 1}, {1, 33}, {33, 1}, {31, 17}, {64, 48}, {641, 5}};
  const int ranges[] = {0, 1, 16, 32, 200};
  int n = 0;
  for (const auto& [w, h] : sizes) {
    for (int window : {0, 1, 8, 100, 2000}) {
      for (int invalidPercent : {0, 15, 50}) {
        StereoParams p;
        p.minDisparity = n % 2 ? -8 : 0;
        p.numDisparities = 32;
        p.speckleWindowSize = window;
        p.speckleRange = ranges[n % 5];
        ++n;
        const TestImage d =
            randomDisparityMap(w, h, p, static_cast<std::uint64_t>(n * 7919), invalidPercent);
        SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h) + ", invalid " +
                     std::to_string(invalidPercent) + "%, " + describe(p));
        TestImage ref = d.clone();
        filterSpeckles(ref.view(), p, scalarBackend());
        for (const Layout& layout : kLayouts) {
          SCOPED_TRACE(std::string("layout ") + layout.name);
          TestImage out = d.clone(layout);
          filterSpeckles(out.view(), p, backend);
          CONFORM(sameImage(ref.view(), out.view()), "disparity");
          CONFORM(out.canariesIntact(), "disparity");
        }
      }
    }
  }
}

// ---------------------------------------------------------------------------
// Median

void conformMedianFilter(const Backend& backend) {
  const std::pair<int, int> sizes[] = {{1, 1},   {2, 2},  {1, 33}, {33, 1},
                                       {31, 17}, {64, 9}, {641, 6}};
  int n = 0;
  for (const auto& [w, h] : sizes) {
    for (int k : {3, 5}) {
      for (int minValidToFill : {0, 1, 4, 9, 25}) {
        if (minValidToFill > k * k) continue;
        for (int invalidPercent : {0, 30, 80, 100}) {
          ++n;
          StereoParams sp;
          sp.minDisparity = n % 2 ? -8 : 0;
          sp.numDisparities = 64;
          const std::int16_t inv = invalidDisparity(sp);
          TestImage src =
              randomDisparityMap(w, h, sp, static_cast<std::uint64_t>(n), invalidPercent);
          if (n % 3 == 0) {
            // The whole int16 range, extremes included (overflow in vector code).
            Rng rng(static_cast<std::uint64_t>(n));
            for (int y = 0; y < h; ++y)
              for (int x = 0; x < w; ++x)
                if (src.at<std::int16_t>(x, y) != inv) {
                  const int pick = rng.uniform(0, 3);
                  src.at<std::int16_t>(x, y) =
                      static_cast<std::int16_t>(pick == 0   ? -32768
                                                : pick == 1 ? 32767
                                                            : rng.uniform(-32768, 32767));
                }
          }
          MedianParams m;
          m.kernelSize = k;
          m.minValidToFill = minValidToFill;
          SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h) + ", kernel " +
                       std::to_string(k) + ", minValidToFill " + std::to_string(minValidToFill) +
                       ", invalid " + std::to_string(invalidPercent) + "%");
          TestImage ref(w, h, PixelType::S16C1);
          medianFilter(src.view(), ref.view(), m, inv, scalarBackend());
          for (const Layout& layout : kLayouts) {
            SCOPED_TRACE(std::string("layout ") + layout.name);
            const TestImage in = src.clone(layout);
            TestImage out(w, h, PixelType::S16C1, layout);
            out.fillBytes(0x99);
            medianFilter(in.view(), out.view(), m, inv, backend);
            CONFORM(sameImage(ref.view(), out.view()), "median output");
            CONFORM(out.canariesIntact(), "median output");
            CONFORM(untouched(src, in, "median input"), "median input");
          }
        }
      }
    }
  }
}

// ---------------------------------------------------------------------------
// Horopter mask

void conformHoropterMask(const Backend& backend) {
  const std::pair<int, int> sizes[] = {{1, 1},  {1, 9},  {31, 3}, {32, 4},
                                       {33, 5}, {64, 7}, {65, 2}, {641, 3}};
  int n = 0;
  for (const auto& [w, h] : sizes) {
    for (int kind = 0; kind < 3; ++kind) {  // no image, U8C1, U8C3
      ++n;
      const std::int16_t inv = static_cast<std::int16_t>(n % 2 ? -16 : -144);
      TestImage d =
          randomImage(w, h, PixelType::S16C1, static_cast<std::uint64_t>(n), -32768, 32767);
      Rng rng(static_cast<std::uint64_t>(n) + 3);
      std::vector<std::int16_t> thresholds(static_cast<std::size_t>(w));
      for (auto& t : thresholds) {
        const int pick = rng.uniform(0, 5);
        t = static_cast<std::int16_t>(pick == 0   ? 32767
                                      : pick == 1 ? -32768
                                      : pick == 2 ? inv
                                                  : rng.uniform(-200, 1200));
      }
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          const int pick = rng.uniform(0, 4);
          if (pick == 0) d.at<std::int16_t>(x, y) = inv;
          if (pick == 1) d.at<std::int16_t>(x, y) = thresholds[x];
          if (pick == 2)
            d.at<std::int16_t>(x, y) = static_cast<std::int16_t>(rng.uniform(-200, 1200));
        }
      const PixelType imageType = kind == 2 ? PixelType::U8C3 : PixelType::U8C1;
      const TestImage image =
          randomImage(w, h, imageType, static_cast<std::uint64_t>(n) + 9, 0, 255);
      SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h) + ", image kind " +
                   std::to_string(kind));
      TestImage refMask(w, h, PixelType::U8C1), refSegmented(w, h, imageType);
      horopterMask(d.view(), thresholds, inv, refMask.view(),
                   kind ? image.cview() : ConstImageView{},
                   kind ? refSegmented.view() : ImageView{}, scalarBackend());
      for (const Layout& layout : kLayouts) {
        SCOPED_TRACE(std::string("layout ") + layout.name);
        const TestImage din = d.clone(layout), img = image.clone(layout);
        TestImage mask(w, h, PixelType::U8C1, layout), segmented(w, h, imageType, layout);
        mask.fillBytes(0x42);
        segmented.fillBytes(0x42);
        horopterMask(din.view(), thresholds, inv, mask.view(),
                     kind ? img.cview() : ConstImageView{}, kind ? segmented.view() : ImageView{},
                     backend);
        CONFORM(sameImage(refMask.view(), mask.view()), "mask");
        if (kind) {
          CONFORM(sameImage(refSegmented.view(), segmented.view()), "segmented");
        }
        CONFORM(mask.canariesIntact(), "mask");
        CONFORM(segmented.canariesIntact(), "segmented");
        CONFORM(untouched(d, din, "disparity"), "disparity");
        CONFORM(untouched(image, img, "image"), "image");
      }
    }
  }
}

TEST_P(Conformance, PrefilterXSobel) {
  conformPrefilterXSobel(backend());
}
TEST_P(Conformance, PrefilterNormalized) {
  conformPrefilterNormalized(backend());
}
TEST_P(Conformance, MatchBlocks) {
  conformMatchBlocks(backend());
}
TEST_P(Conformance, MatchBlocksGuardBelowRange) {
  conformMatchBlocksGuarded(backend());
}
TEST_P(Conformance, MatchBlocksLeftBand) {
  conformMatchBlocksLeftBand(backend());
}
TEST_P(Conformance, LeftRightCheck) {
  conformLeftRightCheck(backend());
}
TEST_P(Conformance, FilterSpeckles) {
  conformFilterSpeckles(backend());
}
TEST_P(Conformance, MedianFilter) {
  conformMedianFilter(backend());
}
TEST_P(Conformance, HoropterMask) {
  conformHoropterMask(backend());
}

// ---------------------------------------------------------------------------
// Self-tests: deliberately wrong backends, each of which the checks above must
// catch (with exactly one failure). They prove the conformance suite can fail.

namespace wrong {

// Matching one 1/16 px off at a single pixel.
void matchOffByOne(const ConstImageView& l, const ConstImageView& r, const ConstImageView& t,
                   const StereoParams& p, const BelowRangeGuard& g, const ImageView& d,
                   const ImageView& wr, RowRange rows) {
  scalarBackend().kernels->matchBlocks(l, r, t, p, g, d, wr, rows);
  if (rows.begin <= d.height / 2 && d.height / 2 < rows.end)
    d.row<std::int16_t>(d.height / 2)[d.width / 2] += 1;
}
// Writes one pixel past the end of the first row when the stride has room
// (a canary there; never outside the buffer, so AddressSanitizer stays quiet).
void medianOverrun(const ConstImageView& s, const ImageView& d, int k, int minValid,
                   std::int16_t invalid, RowRange rows) {
  scalarBackend().kernels->medianFilter(s, d, k, minValid, invalid, rows);
  if (d.strideBytes >= static_cast<std::ptrdiff_t>((d.width + 1) * sizeof(std::int16_t)))
    d.row<std::int16_t>(0)[d.width] = 0x1234;
}
// Assumes tightly packed rows.
void prefilterIgnoresStride(const ConstImageView& s, int cap, const ImageView& f,
                            const ImageView& t, RowRange rows) {
  ConstImageView src = s;
  src.strideBytes = s.width;
  ImageView filtered = f, texture = t;
  filtered.strideBytes = f.width;
  texture.strideBytes = t.width;
  scalarBackend().kernels->prefilterXSobel(src, cap, filtered, texture, rows);
}
// The normalized response of each row stripe as if the stripe were the whole
// image: the window's rows above and below the stripe are not read.
void normalizedStripeLocal(const ConstImageView& s, int cap, int size, const ImageView& f,
                           const ImageView& t, RowRange rows) {
  const auto slice = [&](auto view) {
    if (view.empty()) return view;
    view.data = view.template row<std::uint8_t>(rows.begin);
    view.height = rows.end - rows.begin;
    return view;
  };
  if (rows.end <= rows.begin) return;
  scalarBackend().kernels->prefilterNormalized(slice(s), cap, size, slice(f), slice(t),
                                               RowRange{0, rows.end - rows.begin});
}
// Scribbles on its (const) input.
void maskModifiesInput(const ConstImageView& d, std::span<const std::int16_t> thresholds,
                       std::int16_t invalid, const ImageView& mask, const ConstImageView& image,
                       const ImageView& segmented, RowRange rows) {
  scalarBackend().kernels->horopterMask(d, thresholds, invalid, mask, image, segmented, rows);
  const_cast<std::int16_t*>(d.row<std::int16_t>(0))[0] ^= 1;
}
// Never removes a speckle.
void speckleNoop(const ImageView&, const StereoParams&) {}
// Rounds the left disparity down instead of to nearest.
void lrTruncates(const ImageView& d, const ConstImageView& wr, const StereoParams& p,
                 RowRange rows) {
  TestImage shifted = copyOf(d);
  const std::int16_t invalid = invalidDisparity(p);
  for (int y = 0; y < d.height; ++y)
    for (int x = 0; x < d.width; ++x)
      if (shifted.at<std::int16_t>(x, y) != invalid) shifted.at<std::int16_t>(x, y) &= ~15;
  TestImage checked = shifted.clone();
  scalarBackend().kernels->leftRightCheck(checked.view(), wr, p, rows);
  for (int y = rows.begin; y < rows.end; ++y)
    for (int x = 0; x < d.width; ++x)
      if (checked.at<std::int16_t>(x, y) == invalid) d.row<std::int16_t>(y)[x] = invalid;
}

Backend make(const char* name) {
  Backend b = scalarBackend();
  b.name = name;
  b.description = "deliberately wrong, for the conformance self-tests";
  return b;
}

const Backend& offByOne() {
  static const Backend b = [] {
    Backend x = make("wrong-match");
    KernelTable t = *x.kernels;
    t.matchBlocks = matchOffByOne;
    x.kernels = std::make_shared<const KernelTable>(t);
    return x;
  }();
  return b;
}
const Backend& overrun() {
  static const Backend b = [] {
    Backend x = make("wrong-median");
    KernelTable t = *x.kernels;
    t.medianFilter = medianOverrun;
    x.kernels = std::make_shared<const KernelTable>(t);
    return x;
  }();
  return b;
}
const Backend& strideless() {
  static const Backend b = [] {
    Backend x = make("wrong-prefilter");
    KernelTable t = *x.kernels;
    t.prefilterXSobel = prefilterIgnoresStride;
    x.kernels = std::make_shared<const KernelTable>(t);
    return x;
  }();
  return b;
}
const Backend& stripeLocal() {
  static const Backend b = [] {
    Backend x = make("wrong-normalized");
    KernelTable t = *x.kernels;
    t.prefilterNormalized = normalizedStripeLocal;
    x.kernels = std::make_shared<const KernelTable>(t);
    return x;
  }();
  return b;
}
const Backend& scribbler() {
  static const Backend b = [] {
    Backend x = make("wrong-mask");
    KernelTable t = *x.kernels;
    t.horopterMask = maskModifiesInput;
    x.kernels = std::make_shared<const KernelTable>(t);
    return x;
  }();
  return b;
}
const Backend& noSpeckles() {
  static const Backend b = [] {
    Backend x = make("wrong-speckles");
    KernelTable t = *x.kernels;
    t.filterSpeckles = speckleNoop;
    x.kernels = std::make_shared<const KernelTable>(t);
    return x;
  }();
  return b;
}
const Backend& truncatingCheck() {
  static const Backend b = [] {
    Backend x = make("wrong-lr");
    KernelTable t = *x.kernels;
    t.leftRightCheck = lrTruncates;
    x.kernels = std::make_shared<const KernelTable>(t);
    return x;
  }();
  return b;
}

}  // namespace wrong

TEST(ConformanceSelfTest, CatchesEachKindOfDeviation) {
  EXPECT_NONFATAL_FAILURE(conformMatchBlocks(wrong::offByOne()), "pixels differ");
  EXPECT_NONFATAL_FAILURE(conformMedianFilter(wrong::overrun()), "canary");
  EXPECT_NONFATAL_FAILURE(conformPrefilterXSobel(wrong::strideless()), "layout padded");
  EXPECT_NONFATAL_FAILURE(conformPrefilterNormalized(wrong::stripeLocal()), "pixels differ");
  EXPECT_NONFATAL_FAILURE(conformHoropterMask(wrong::scribbler()), "disparity was modified");
  EXPECT_NONFATAL_FAILURE(conformFilterSpeckles(wrong::noSpeckles()), "pixels differ");
  EXPECT_NONFATAL_FAILURE(conformLeftRightCheck(wrong::truncatingCheck()), "pixels differ");
}

void compareFrontends(const Backend& backend, const ConstImageView& left,
                      const ConstImageView& right, const StereoParams& p, const MedianParams& m,
                      const ConstImageView& colour);

TEST(ConformanceSelfTest, FrontendComparisonCatchesADeviatingStage) {
  EXPECT_NONFATAL_FAILURE(
      {
        const StereoPair pair = stepScenePair(120, 40, StepScene{60, 100, 8, 32, 20, 4}, 1);
        StereoParams p;
        p.numDisparities = 32;
        compareFrontends(wrong::noSpeckles(), pair.left.view(), pair.right.view(), p,
                         MedianParams{}, ConstImageView{});
      },
      "cleaned disparity");
}

// ---------------------------------------------------------------------------
// The whole front end

// Runs both front ends on the pair and compares every output.
void compareFrontends(const Backend& backend, const ConstImageView& left,
                      const ConstImageView& right, const StereoParams& p, const MedianParams& m,
                      const ConstImageView& colour) {
  StereoFrontend ref(p, m, scalarBackend());
  StereoFrontend test(p, m, backend);
  ref.computeDisparity(left, right);
  test.computeDisparity(left, right);
  CONFORM(sameImage(ref.cleanedDisparity().view(), test.cleanedDisparity().view()),
          "cleaned disparity");
  CONFORM(sameImage(ref.disparity().view(), test.disparity().view()), "final disparity");
  // The zone of a fixation in the middle of the range, or, for ranges that
  // are not in front of the cameras, a ramp of thresholds across the range.
  const double middle = p.minDisparity + p.numDisparities / 2.0;
  std::vector<std::int16_t> thresholds(static_cast<std::size_t>(left.width));
  if (middle > 0) {
    RectifiedGeometry g;
    g.focalPx = left.width;
    g.cx = (left.width - 1) / 2.0;
    g.baseline = 1;
    thresholds = horopterThresholds(g, left.width, fixationFromDisparity(g, g.cx, middle));
  } else {
    for (int u = 0; u < left.width; ++u)
      thresholds[u] =
          static_cast<std::int16_t>(16 * p.minDisparity + (u * 37) % (16 * p.numDisparities));
  }
  ref.computeMask(thresholds, colour);
  test.computeMask(thresholds, colour);
  CONFORM(sameImage(ref.mask().view(), test.mask().view()), "mask");
  if (!colour.empty()) {
    CONFORM(sameImage(ref.segmented().view(), test.segmented().view()), "segmented");
  }
}

TEST_P(Conformance, FrontendOnSyntheticScenes) {
  struct Setting {
    const char* what;
    StereoParams p;
    MedianParams m;
  };
  std::vector<Setting> settings;
  settings.push_back({"defaults", StereoParams{}, MedianParams{}});
  {
    StereoParams p;
    p.numDisparities = 32;
    p.blockSize = 5;
    p.preFilterType = PreFilterType::None;
    MedianParams m;
    m.kernelSize = 3;
    settings.push_back({"raw, block 5, median 3", p, m});
    p.minDisparity = -8;
    p.textureThreshold = 0;
    p.uniquenessRatio = 0;
    p.disp12MaxDiff = -1;
    m.kernelSize = 0;
    settings.push_back({"negative range, all checks off", p, m});
    StereoParams q;
    q.numDisparities = 48;
    q.blockSize = 15;
    q.speckleWindowSize = 0;
    q.disp12MaxDiff = 0;
    MedianParams m5;
    m5.minValidToFill = 1;
    settings.push_back({"block 15, no speckles, strict check, fill any hole", q, m5});
  }
  for (const Setting& s : settings) {
    for (const Layout& layout : kLayouts) {
      SCOPED_TRACE(std::string(s.what) + ", layout " + layout.name);
      const StepScene scene{
          90, 150, 20, 70, s.p.minDisparity + s.p.numDisparities - 6, s.p.minDisparity + 3};
      const StereoPair pair = stepScenePair(193, 91, scene, 4242);
      const TestImage left = pair.left.clone(layout), right = pair.right.clone(layout);
      const TestImage colour = randomImage(193, 91, PixelType::U8C3, 7, 0, 255, layout);
      compareFrontends(backend(), left.view(), right.view(), s.p, s.m, colour.view());
      CONFORM(left.canariesIntact(), "left input");
      CONFORM(right.canariesIntact(), "right input");
    }
  }
}

// Zone-limited matching (zone_search.hpp): the ranges the zone gives, from
// the horopter thresholds of fixations across the range, searched by each
// backend's front end, with and without the guard below the range, equal
// the reference front end over the same range.
TEST_P(Conformance, FrontendZoneLimitedRanges) {
  struct Setting {
    int width, height;
    StereoParams p;
    ZoneSearch zone;
  };
  std::vector<Setting> settings;
  {
    StereoParams p;  // defaults: 0..63, block 9
    ZoneSearch zone;
    zone.enabled = 1;
    zone.guardStep = 0;
    settings.push_back({193, 41, p, zone});
    zone.guardStep = 3;
    settings.push_back({193, 41, p, zone});
    zone.marginPx = 0;
    zone.maxDisparity = 79;  // past the full range's top (near hands)
    zone.guardStep = 1;
    settings.push_back({161, 33, p, zone});
    p.numDisparities = 96;
    p.blockSize = 5;
    zone.marginPx = 9;
    zone.maxDisparity = 127;
    zone.guardStep = 2;
    settings.push_back({641, 17, p, zone});
    p.minDisparity = -8;  // checked disparities below zero
    p.numDisparities = 48;
    zone.maxDisparity = 0;
    zone.marginPx = 2;
    zone.guardStep = 5;
    settings.push_back({97, 29, p, zone});
  }
  int n = 0;
  long long guarded = 0;  // pixels the guard changed in the reference
  for (const Setting& s : settings) {
    for (double fixation : {0.25, 0.5, 0.8}) {
      const int top = largestDisparity(s.p, s.zone);
      RectifiedGeometry g;
      g.focalPx = s.width;
      g.cx = (s.width - 1) / 2.0;
      g.baseline = 1;
      const double fixationPx = std::max(1.0, fixation * top);
      const std::vector<std::int16_t> thresholds =
          horopterThresholds(g, s.width, fixationFromDisparity(g, g.cx, fixationPx));
      const SearchRange range = zoneSearchRange(s.p, thresholds, s.zone);
      SCOPED_TRACE("width " + std::to_string(s.width) + ", range " +
                   std::to_string(range.minDisparity) + " + " +
                   std::to_string(range.numDisparities));
      const StepScene scene{s.width / 4,  s.width * 3 / 4, 3,
                            s.height - 3, top - 4,         std::max(s.p.minDisparity, 1) + 2};
      const StereoPair pair = stepScenePair(s.width, s.height, scene, 900 + n++);
      StereoFrontend ref(s.p, MedianParams{}, reference());
      StereoFrontend test(s.p, MedianParams{}, backend());
      ref.computeDisparity(pair.left.view(), pair.right.view(), range);
      test.computeDisparity(pair.left.view(), pair.right.view(), range);
      CONFORM(sameImage(ref.cleanedDisparity().view(), test.cleanedDisparity().view()),
              "cleaned disparity");
      CONFORM(sameImage(ref.disparity().view(), test.disparity().view()), "final disparity");
      ref.computeMask(thresholds);
      test.computeMask(thresholds);
      CONFORM(sameImage(ref.mask().view(), test.mask().view()), "mask");
      if (range.guardStep > 0) {
        StereoFrontend plain(s.p, MedianParams{}, reference());
        plain.computeDisparity(pair.left.view(), pair.right.view(),
                               {range.minDisparity, range.numDisparities});
        const ConstImageView a = plain.cleanedDisparity().view(), b = ref.cleanedDisparity().view();
        for (int y = 0; y < a.height; ++y)
          for (int x = 0; x < a.width; ++x)
            guarded += a.row<std::int16_t>(y)[x] != b.row<std::int16_t>(y)[x];
      }
    }
  }
  EXPECT_GT(guarded, 0) << "the guard changed no pixel: its settings test nothing";
}

// Random points of the whole parameter space, random sizes and layouts,
// through the front end (every kernel, mask and segmentation included).
TEST_P(Conformance, FrontendRandomConfigurations) {
  Rng rng(777);
  for (int run = 0; run < 150; ++run) {
    StereoParams p;
    p.blockSize = 2 * rng.uniform(1, 20) + 1;
    p.numDisparities = 16 * rng.uniform(1, 8);
    p.minDisparity = rng.uniform(-40, 40);
    const int type = rng.uniform(0, 3);  // XSobel twice as often as the others
    p.preFilterType = type == 0   ? PreFilterType::None
                      : type == 1 ? PreFilterType::NormalizedResponse
                                  : PreFilterType::XSobel;
    p.preFilterSize = 2 * rng.uniform(2, 20) + 1;
    p.preFilterCap = rng.uniform(1, 63);
    p.textureThreshold = rng.chance(30) ? 0 : rng.uniform(1, 400);
    p.uniquenessRatio = rng.chance(30) ? 0 : rng.uniform(1, 100);
    p.disp12MaxDiff = rng.uniform(-1, 3);
    p.speckleWindowSize = rng.chance(20) ? 0 : rng.uniform(1, 300);
    p.speckleRange = rng.uniform(0, 64);
    MedianParams m;
    const int kernelSizes[] = {0, 3, 5};
    m.kernelSize = kernelSizes[rng.uniform(0, 2)];
    m.minValidToFill = m.kernelSize ? rng.uniform(0, m.kernelSize * m.kernelSize) : 0;
    const int needed = p.blockSize + std::max(p.minDisparity + p.numDisparities - 1, 0) -
                       std::min(p.minDisparity, 0);
    const int w = needed + rng.uniform(0, 300 - std::min(needed, 250));
    const int h = p.blockSize + rng.uniform(0, 60);
    const Layout& layout = kLayouts[rng.uniform(0, 2)];
    SCOPED_TRACE("run " + std::to_string(run) + ": " + std::to_string(w) + "x" + std::to_string(h) +
                 ", layout " + layout.name + ", median " + std::to_string(m.kernelSize) + "/" +
                 std::to_string(m.minValidToFill) + ", " + describe(p));
    const int nearD = p.minDisparity + rng.uniform(p.numDisparities / 2, p.numDisparities - 1);
    const int farD = p.minDisparity + rng.uniform(0, p.numDisparities / 2);
    const int x0 = rng.uniform(0, w - 1), y0 = rng.uniform(0, h - 1);
    const StereoPair pair =
        stepScenePair(w, h,
                      StepScene{x0, std::min(w, x0 + rng.uniform(1, w)), y0,
                                std::min(h, y0 + rng.uniform(1, h)), nearD, farD},
                      rng.next());
    const TestImage left = pair.left.clone(layout), right = pair.right.clone(layout);
    const TestImage colour = randomImage(w, h, PixelType::U8C3, rng.next(), 0, 255, layout);
    compareFrontends(backend(), left.view(), right.view(), p, m,
                     rng.chance(50) ? colour.cview() : left.cview());
    if (HasFailure()) return;
  }
}

// Real pairs (../shared/data), through the front end and the backend, with a
// few settings each.
void compareOnRealPair(const Backend& backend, const std::string& leftPath,
                       const std::string& rightPath, int numDisparities, const cv::Rect& roi) {
  const cv::Mat leftColour = cv::imread(leftPath, cv::IMREAD_COLOR);
  const cv::Mat rightColour = cv::imread(rightPath, cv::IMREAD_COLOR);
  ASSERT_FALSE(leftColour.empty()) << leftPath;
  ASSERT_FALSE(rightColour.empty()) << rightPath;
  cv::Mat left, right;
  cv::cvtColor(leftColour, left, cv::COLOR_BGR2GRAY);
  cv::cvtColor(rightColour, right, cv::COLOR_BGR2GRAY);
  // Views into the middle of the full images: a non-zero origin and the full
  // image's stride.
  const cv::Rect r = roi.area() > 0 ? roi : cv::Rect(0, 0, left.cols, left.rows);
  const cv::Mat l = left(r), rr = right(r), c = leftColour(r);
  StereoParams defaults;
  defaults.numDisparities = numDisparities;
  StereoParams small = defaults;
  small.blockSize = 5;
  small.minDisparity = -4;
  small.preFilterCap = 15;
  small.uniquenessRatio = 5;
  small.speckleRange = 16;
  StereoParams raw = defaults;
  raw.blockSize = 15;
  raw.preFilterType = PreFilterType::None;
  raw.textureThreshold = 0;
  raw.disp12MaxDiff = -1;
  StereoParams normalized = defaults;  // cv::StereoBM's other prefilter, its default window
  normalized.preFilterType = PreFilterType::NormalizedResponse;
  normalized.blockSize = 21;
  MedianParams m3;
  m3.kernelSize = 3;
  const std::pair<StereoParams, MedianParams> settings[] = {
      {defaults, MedianParams{}}, {small, m3}, {raw, MedianParams{}}, {normalized, MedianParams{}}};
  int n = 0;
  for (const auto& [p, m] : settings) {
    SCOPED_TRACE("setting " + std::to_string(n++) + ": " + describe(p));
    compareFrontends(backend, viewOf(l), viewOf(rr), p, m, viewOf(c));
  }
}

TEST_P(Conformance, FrontendOnTsukuba) {
  const std::string dir = sharedDataDir() + "/middlebury/tsukuba";
  HOROPTER_REQUIRE_FILE(dir + "/im3.png");
  HOROPTER_REQUIRE_FILE(dir + "/im4.png");
  compareOnRealPair(backend(), dir + "/im3.png", dir + "/im4.png", 16, {});
}

TEST_P(Conformance, FrontendOnTeddy) {
  const std::string dir = sharedDataDir() + "/middlebury/teddy";
  HOROPTER_REQUIRE_FILE(dir + "/im2.png");
  HOROPTER_REQUIRE_FILE(dir + "/im6.png");
  compareOnRealPair(backend(), dir + "/im2.png", dir + "/im6.png", 64, {});
}

TEST_P(Conformance, FrontendOnAloeRoi) {
  const std::string dir = sharedDataDir() + "/middlebury/aloe";
  HOROPTER_REQUIRE_FILE(dir + "/aloeL.jpg");
  HOROPTER_REQUIRE_FILE(dir + "/aloeR.jpg");
  compareOnRealPair(backend(), dir + "/aloeL.jpg", dir + "/aloeR.jpg", 128,
                    cv::Rect(401, 333, 333, 201));
}

// A grey 640x480 JPEG pair (OpenCV's calibration chessboards; not rectified,
// which does not matter for conformance): flat areas and hard edges.
TEST_P(Conformance, FrontendOnChessboardPair) {
  const std::string dir = sharedDataDir() + "/opencv_stereo_calib";
  HOROPTER_REQUIRE_FILE(dir + "/left01.jpg");
  HOROPTER_REQUIRE_FILE(dir + "/right01.jpg");
  compareOnRealPair(backend(), dir + "/left01.jpg", dir + "/right01.jpg", 32, {});
}

}  // namespace
}  // namespace horopter::test
