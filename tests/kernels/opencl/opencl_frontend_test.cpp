// The asynchronous OpenCL front end: several frames in flight give the
// scalar front end's results in order; stage times come from profiling
// events; an injected build or enqueue failure falls back to the CPU
// without losing or reordering frames; a bad device name is an error. The
// chains run with both shapes of the SAD matcher (HOROPTER_OPENCL_SAD).
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "common/cpu_backend.hpp"
#include "horopter/core/error.hpp"
#include "horopter/vision/frontend.hpp"
#include "horopter/vision/opencl_frontend.hpp"
#include "opencl/launch.hpp"
#include "opencl/pipeline.hpp"
#include "opencl/program_cache.hpp"
#include "opencl_support.hpp"
#include "scoped_env.hpp"
#include "test_support.hpp"

namespace horopter::test {
namespace {

struct Setting {
  const char* what;
  StereoParams stereo;
  MedianParams median;
};

std::vector<Setting> settings() {
  std::vector<Setting> out;
  out.push_back({"defaults (speckles on the CPU, median 5)", StereoParams{}, MedianParams{}});
  StereoParams noSpeckles;
  noSpeckles.numDisparities = 32;
  noSpeckles.speckleWindowSize = 0;
  MedianParams median3;
  median3.kernelSize = 3;
  out.push_back({"no speckles: the whole chain on the device", noSpeckles, median3});
  StereoParams raw = noSpeckles;
  raw.preFilterType = PreFilterType::None;
  raw.disp12MaxDiff = -1;
  raw.minDisparity = -5;
  MedianParams off;
  off.kernelSize = 0;
  out.push_back({"raw, no check, no median", raw, off});
  StereoParams speckleNoMedian;
  speckleNoMedian.numDisparities = 16;
  speckleNoMedian.blockSize = 7;
  out.push_back({"speckles, no median", speckleNoMedian, off});
  StereoParams normalized = stereoBMDefaults(32, 11);  // cv::StereoBM's other prefilter
  normalized.preFilterType = PreFilterType::NormalizedResponse;
  normalized.preFilterSize = 13;
  out.push_back({"StereoBM's defaults, normalized response", normalized, off});
  StereoParams band = noSpeckles;  // sad_band.cl after the region's kernels, on the device
  band.leftBand = 16;
  out.push_back({"left band of 16, no speckles", band, median3});
  return out;
}

// The SAD matcher's shapes (kernels/opencl/launch.hpp).
constexpr const char* kSadShapes[] = {"strip", "tiled"};

std::vector<StereoPair> frames(int count) {
  std::vector<StereoPair> out;
  for (int i = 0; i < count; ++i)
    out.push_back(stepScenePair(157 + 8 * i, 61, StepScene{40, 110, 10, 50, 30 + i, 6 + i},
                                static_cast<std::uint64_t>(100 + i)));
  return out;
}

// Scalar front-end results, one per frame.
std::vector<TestImage> expected(const Setting& s, const std::vector<StereoPair>& pairs) {
  StereoFrontend ref(s.stereo, s.median, scalarBackend());
  std::vector<TestImage> out;
  for (const StereoPair& p : pairs)
    out.push_back(copyOf(ref.computeDisparity(p.left.view(), p.right.view()).view()));
  return out;
}

// A two-slot OpenCL front end for `s`, frame by frame, against the scalar
// front end's results; returned for the caller's further checks.
std::unique_ptr<OpenClFrontend> expectFramesEqualScalar(const Setting& s,
                                                        const std::vector<StereoPair>& pairs) {
  const std::vector<TestImage> want = expected(s, pairs);
  auto frontend = std::make_unique<OpenClFrontend>(s.stereo, s.median, "opencl", 2);
  EXPECT_FALSE(frontend->onCpu()) << frontend->fallbackReason();
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const Image& got = frontend->computeDisparity(pairs[i].left.view(), pairs[i].right.view());
    EXPECT_TRUE(sameImage(want[i].view(), got.view())) << "frame " << i;
  }
  return frontend;
}

TEST(OpenClFrontend, FramesInFlightEqualTheScalarFrontendInOrder) {
  HOROPTER_REQUIRE_OPENCL_DEVICE();
  const std::vector<StereoPair> pairs = frames(5);
  for (const char* shape : kSadShapes)
    for (const Setting& s : settings()) {
      const ScopedEnv sad("HOROPTER_OPENCL_SAD", shape);
      SCOPED_TRACE(std::string(s.what) + ", SAD " + shape);
      const std::vector<TestImage> want = expected(s, pairs);
      OpenClFrontend frontend(s.stereo, s.median, "opencl", 3);
      ASSERT_FALSE(frontend.onCpu()) << frontend.fallbackReason();
      // Three in flight, then one at a time; the fourth submit completes the first.
      std::vector<OpenClFrontend::Ticket> tickets;
      for (std::size_t i = 0; i < 3; ++i)
        tickets.push_back(frontend.submit(pairs[i].left.view(), pairs[i].right.view()));
      for (std::size_t i = 0; i < 3; ++i)
        EXPECT_TRUE(sameImage(want[i].view(), frontend.wait(tickets[i]).view())) << "frame " << i;
      for (std::size_t i = 3; i < pairs.size(); ++i) {
        const Image& got = frontend.computeDisparity(pairs[i].left.view(), pairs[i].right.view());
        EXPECT_TRUE(sameImage(want[i].view(), got.view())) << "frame " << i;
      }
      EXPECT_FALSE(frontend.onCpu());
    }
}

// Zone-limited matching: frames in flight, each over its own search range
// (two with the guard below the range), equal the scalar front end over the
// same ranges (the invalid marker rewritten as the configured range's).
TEST(OpenClFrontend, EachFrameSearchesItsOwnRange) {
  HOROPTER_REQUIRE_OPENCL_DEVICE();
  const std::vector<StereoPair> pairs = frames(4);
  const SearchRange ranges[] = {{16, 48, 3}, {0, 64}, {32, 32, 1}, {8, 48}};
  for (const char* shape : kSadShapes)
    for (const Setting& s : settings()) {
      if (s.stereo.minDisparity != 0 || s.stereo.numDisparities < 32) continue;
      const ScopedEnv sad("HOROPTER_OPENCL_SAD", shape);
      SCOPED_TRACE(std::string(s.what) + ", SAD " + shape);
      StereoFrontend ref(s.stereo, s.median, scalarBackend());
      OpenClFrontend frontend(s.stereo, s.median, "opencl", 4);
      ASSERT_FALSE(frontend.onCpu()) << frontend.fallbackReason();
      std::vector<OpenClFrontend::Ticket> tickets;
      for (std::size_t i = 0; i < pairs.size(); ++i) {
        const SearchRange r = s.stereo.numDisparities == 64 ? ranges[i] : SearchRange{16, 16};
        tickets.push_back(frontend.submit(pairs[i].left.view(), pairs[i].right.view(), r));
      }
      for (std::size_t i = 0; i < pairs.size(); ++i) {
        const SearchRange r = s.stereo.numDisparities == 64 ? ranges[i] : SearchRange{16, 16};
        const Image& want = ref.computeDisparity(pairs[i].left.view(), pairs[i].right.view(), r);
        EXPECT_TRUE(sameImage(want.view(), frontend.wait(tickets[i]).view())) << "frame " << i;
      }
    }
}

TEST(OpenClFrontend, ProfileNamesEveryStage) {
  HOROPTER_REQUIRE_OPENCL_DEVICE();
  const std::vector<StereoPair> pairs = frames(1);
  for (const char* shape : kSadShapes) {
    SCOPED_TRACE(shape);
    const ScopedEnv sad("HOROPTER_OPENCL_SAD", shape);
    OpenClFrontend frontend(StereoParams{}, MedianParams{}, "opencl", 1);
    frontend.computeDisparity(pairs[0].left.view(), pairs[0].right.view());
    std::vector<std::string> stages;
    for (const OpenClStageTime& t : frontend.profile()) {
      EXPECT_EQ(std::count(stages.begin(), stages.end(), t.stage), 0) << "twice: " << t.stage;
      stages.push_back(t.stage);
      EXPECT_GE(t.ms, 0.0) << t.stage;
    }
    std::vector<std::string> want = {"upload left",
                                     "prefilter left",
                                     "left-right check",
                                     "download",
                                     "speckle filter (CPU, " + cpuBackend().name + ")",
                                     "median"};
    if (std::string(shape) == "strip")
      want.push_back("match");
    else
      want.insert(want.end(), {"match costs", "match decide"});
    for (const std::string& stage : want)
      EXPECT_NE(std::find(stages.begin(), stages.end(), stage), stages.end()) << stage;
  }
}

// The left band's kernel (sad_band.cl) runs after either shape's only where
// params.leftBand leaves a band: without one the queue is as before.
TEST(OpenClFrontend, LeftBandKernelRunsOnlyWithABand) {
  HOROPTER_REQUIRE_OPENCL_DEVICE();
  const std::vector<StereoPair> pairs = frames(1);
  for (const char* shape : kSadShapes) {
    const ScopedEnv sad("HOROPTER_OPENCL_SAD", shape);
    for (const int band : {0, 1, 16}) {
      SCOPED_TRACE(std::string(shape) + ", leftBand " + std::to_string(band));
      StereoParams p;
      p.leftBand = band;
      OpenClFrontend frontend(p, MedianParams{}, "opencl", 1);
      frontend.computeDisparity(pairs[0].left.view(), pairs[0].right.view());
      std::vector<std::string> stages;
      for (const OpenClStageTime& t : frontend.profile())
        stages.push_back(t.stage);
      EXPECT_EQ(std::count(stages.begin(), stages.end(), std::string("match left band")),
                band > 0 ? 1 : 0);
    }
  }
}

// A cost volume too large for one allocation is filled band by band: the
// same results, and each stage's time summed into one profile entry.
TEST(OpenClFrontend, TiledMatcherInBandsOfRowsEqualsTheScalarFrontend) {
  HOROPTER_REQUIRE_OPENCL_DEVICE();
  const std::vector<StereoPair> pairs = frames(2);
  const ScopedEnv sad("HOROPTER_OPENCL_SAD", "tiled");
  for (const std::size_t bandBytes : {std::size_t{1}, std::size_t{200000}}) {
    opencl::setTiledBandBytes(bandBytes);  // 1: one row per band
    for (const Setting& s : settings()) {
      SCOPED_TRACE(std::string(s.what) + ", bands of " + std::to_string(bandBytes) + " bytes");
      const std::unique_ptr<OpenClFrontend> frontend = expectFramesEqualScalar(s, pairs);
      std::vector<std::string> stages;
      for (const OpenClStageTime& t : frontend->profile())
        stages.push_back(t.stage);
      EXPECT_EQ(std::count(stages.begin(), stages.end(), std::string("match costs")), 1);
    }
  }
  opencl::setTiledBandBytes(0);
}

// The cost kernel's tuning variants (HOROPTER_OPENCL_TILED): one named, one
// with every knob off its default (odd sizes: partial tiles, passes and
// row groups; block 9 compiled in, the settings' other blocks without it),
// each its own program; the same results, bit for bit.
TEST(OpenClFrontend, TiledMatcherVariantsEqualTheScalarFrontend) {
  HOROPTER_REQUIRE_OPENCL_DEVICE();
  const std::vector<StereoPair> pairs = frames(2);
  const ScopedEnv sad("HOROPTER_OPENCL_SAD", "tiled");
  for (const char* variant : {"rows4-split", "w=16,h=4,planes=3,spread=0,split=2,rows=3,block=9"}) {
    const ScopedEnv tiled("HOROPTER_OPENCL_TILED", variant);
    for (const Setting& s : settings()) {
      SCOPED_TRACE(std::string(s.what) + ", variant " + variant);
      expectFramesEqualScalar(s, pairs);
    }
  }
}

TEST(OpenClFrontend, BadTiledVariantFallsBackWithTheReason) {
  HOROPTER_REQUIRE_OPENCL_DEVICE();
  const ScopedEnv sad("HOROPTER_OPENCL_SAD", "tiled");
  const ScopedEnv tiled("HOROPTER_OPENCL_TILED", "fast");
  OpenClFrontend frontend(settings()[1].stereo, settings()[1].median, "opencl");
  EXPECT_TRUE(frontend.onCpu());
  EXPECT_NE(frontend.fallbackReason().find("HOROPTER_OPENCL_TILED='fast'"), std::string::npos)
      << frontend.fallbackReason();
}

TEST(OpenClFrontend, BadSadShapeFallsBackWithTheReason) {
  HOROPTER_REQUIRE_OPENCL_DEVICE();
  const std::vector<StereoPair> pairs = frames(1);
  const Setting s = settings()[1];
  const std::vector<TestImage> want = expected(s, pairs);
  const ScopedEnv sad("HOROPTER_OPENCL_SAD", "gpu");
  OpenClFrontend frontend(s.stereo, s.median, "opencl");
  EXPECT_TRUE(frontend.onCpu());
  EXPECT_NE(frontend.fallbackReason().find("HOROPTER_OPENCL_SAD='gpu'"), std::string::npos)
      << frontend.fallbackReason();
  EXPECT_TRUE(
      sameImage(want[0].view(),
                frontend.computeDisparity(pairs[0].left.view(), pairs[0].right.view()).view()));
}

TEST(OpenClFrontend, BadDeviceNamesAreErrors) {
  EXPECT_THROW(OpenClFrontend(StereoParams{}, MedianParams{}, "opencl:99"), Error);
  EXPECT_THROW(OpenClFrontend(StereoParams{}, MedianParams{}, "no-such-gpu-anywhere"), Error);
  EXPECT_THROW(OpenClFrontend(StereoParams{}, MedianParams{}, "opencl", 0), Error);
}

// Turns a test hook on for one scope.
class Injected {
 public:
  explicit Injected(void (*hook)(bool)) : hook_(hook) { hook_(true); }
  ~Injected() { hook_(false); }
  Injected(const Injected&) = delete;
  Injected& operator=(const Injected&) = delete;

 private:
  void (*hook_)(bool);
};

TEST(OpenClFrontend, InjectedBuildFailureFallsBackToTheCpu) {
  HOROPTER_REQUIRE_OPENCL_DEVICE();
  const std::vector<StereoPair> pairs = frames(2);
  const Setting s = settings()[0];
  const std::vector<TestImage> want = expected(s, pairs);
  const Injected failing(opencl::setInjectedBuildFailure);
  OpenClFrontend frontend(s.stereo, s.median, "opencl");
  EXPECT_TRUE(frontend.onCpu());
  EXPECT_NE(frontend.fallbackReason().find("injected build failure"), std::string::npos)
      << frontend.fallbackReason();
  for (std::size_t i = 0; i < pairs.size(); ++i)
    EXPECT_TRUE(
        sameImage(want[i].view(),
                  frontend.computeDisparity(pairs[i].left.view(), pairs[i].right.view()).view()));
}

TEST(OpenClFrontend, EnqueueFailureMidStreamLosesAndReordersNothing) {
  HOROPTER_REQUIRE_OPENCL_DEVICE();
  const std::vector<StereoPair> pairs = frames(4);
  const Setting s = settings()[1];
  const std::vector<TestImage> want = expected(s, pairs);
  OpenClFrontend frontend(s.stereo, s.median, "opencl", 4);
  ASSERT_FALSE(frontend.onCpu()) << frontend.fallbackReason();
  std::vector<OpenClFrontend::Ticket> tickets;
  tickets.push_back(frontend.submit(pairs[0].left.view(), pairs[0].right.view()));
  tickets.push_back(frontend.submit(pairs[1].left.view(), pairs[1].right.view()));
  {
    const Injected failing(opencl::setInjectedEnqueueFailure);
    tickets.push_back(frontend.submit(pairs[2].left.view(), pairs[2].right.view()));
  }
  EXPECT_TRUE(frontend.onCpu());
  tickets.push_back(frontend.submit(pairs[3].left.view(), pairs[3].right.view()));
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    EXPECT_EQ(tickets[i], i);
    EXPECT_TRUE(sameImage(want[i].view(), frontend.wait(tickets[i]).view())) << "frame " << i;
  }
}

}  // namespace
}  // namespace horopter::test
