// HOROPTER_BACKEND reaches the OpenCL path's CPU part: forced to scalar, the
// speckle filter of the synchronous kernel table and of the asynchronous
// front end runs the scalar reference, never AVX2; not forced, it runs the
// best CPU backend. (Before, both called avx2::filterSpeckles directly.)
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "common/cpu_backend.hpp"
#include "common/kernel_table.hpp"
#include "horopter/kernels/backend.hpp"
#include "horopter/vision/opencl_frontend.hpp"
#include "opencl/cpu_speckles.hpp"
#include "opencl_support.hpp"
#include "scoped_env.hpp"
#include "test_support.hpp"

namespace horopter::test {
namespace {

// The best CPU backend when nothing is forced.
const Backend& bestCpuBackend() {
  const ScopedEnv unset("HOROPTER_BACKEND", nullptr);
  return cpuBackend();
}

std::vector<std::string> stagesOfOneFrame() {
  const StereoPair pair = stepScenePair(160, 64, StepScene{40, 110, 10, 50, 30, 6}, 7);
  OpenClFrontend frontend(StereoParams{}, MedianParams{}, "opencl", 1);
  frontend.computeDisparity(pair.left.view(), pair.right.view());
  EXPECT_FALSE(frontend.onCpu()) << frontend.fallbackReason();
  std::vector<std::string> stages;
  for (const OpenClStageTime& t : frontend.profile())
    stages.push_back(t.stage);
  return stages;
}

bool contains(const std::vector<std::string>& list, const std::string& item) {
  return std::find(list.begin(), list.end(), item) != list.end();
}

TEST(OpenClForcedBackend, KernelTableSpeckleFilterFollowsIt) {
  HOROPTER_REQUIRE_OPENCL_DEVICE();
  const Backend& device = findBackend("opencl");
  StereoParams params;
  params.speckleWindowSize = 20;
  TestImage d = randomDisparityMap(64, 32, params, 11, 20);
  {
    const ScopedEnv forced("HOROPTER_BACKEND", "scalar");
    device.kernels->filterSpeckles(d.view(), params);
    ASSERT_NE(opencl::lastSpeckleBackend(), nullptr);
    EXPECT_EQ(opencl::lastSpeckleBackend()->name, "scalar");
  }
  {
    const ScopedEnv unset("HOROPTER_BACKEND", nullptr);
    device.kernels->filterSpeckles(d.view(), params);
    EXPECT_EQ(opencl::lastSpeckleBackend(), &bestCpuBackend());
  }
}

TEST(OpenClForcedBackend, FrontendSpeckleFilterFollowsIt) {
  HOROPTER_REQUIRE_OPENCL_DEVICE();
  {
    const ScopedEnv forced("HOROPTER_BACKEND", "scalar");
    const std::vector<std::string> stages = stagesOfOneFrame();
    EXPECT_TRUE(contains(stages, "speckle filter (CPU, scalar)"));
    ASSERT_NE(opencl::lastSpeckleBackend(), nullptr);
    EXPECT_EQ(opencl::lastSpeckleBackend()->name, "scalar");
  }
  {
    const ScopedEnv unset("HOROPTER_BACKEND", nullptr);
    const std::vector<std::string> stages = stagesOfOneFrame();
    EXPECT_TRUE(contains(stages, "speckle filter (CPU, " + bestCpuBackend().name + ")"));
    EXPECT_EQ(opencl::lastSpeckleBackend(), &bestCpuBackend());
  }
}

}  // namespace
}  // namespace horopter::test
