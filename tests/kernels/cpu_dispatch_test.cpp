// CPU dispatch: the AVX2 backend is available exactly where the probe finds
// every instruction set its functions are compiled for, and the CPU backend
// that runs the work device backends leave on the CPU (cpuBackend) follows
// HOROPTER_BACKEND, so that a forced scalar run reaches no AVX2 kernel.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "common/cpu_backend.hpp"
#include "common/cpu_features.hpp"
#include "common/kernel_table.hpp"
#include "horopter/kernels/backend.hpp"
#include "horopter/kernels/devices.hpp"
#include "scoped_env.hpp"

namespace horopter::test {
namespace {

const Backend* backendNamed(const std::string& name) {
  for (const Backend* b : registeredBackends())
    if (b->name == name) return b;
  return nullptr;
}

bool hasFeature(const CpuInfo& cpu, const std::string& feature) {
  return std::find(cpu.features.begin(), cpu.features.end(), feature) != cpu.features.end();
}

bool sameTable(const KernelTable& a, const KernelTable& b) {
  return a.prefilterXSobel == b.prefilterXSobel && a.matchBlocks == b.matchBlocks &&
         a.leftRightCheck == b.leftRightCheck && a.filterSpeckles == b.filterSpeckles &&
         a.medianFilter == b.medianFilter && a.horopterMask == b.horopterMask;
}

TEST(CpuDispatch, Avx2IsAvailableExactlyWhereEveryFeatureIs) {
  const Backend* avx2 = backendNamed("avx2");
  ASSERT_NE(avx2, nullptr);
  EXPECT_EQ(avx2->available, cpuRunsAvx2Backend());
  const CpuInfo cpu = probeCpu();
  const bool all = hasFeature(cpu, "avx2") && hasFeature(cpu, "bmi") && hasFeature(cpu, "bmi2") &&
                   hasFeature(cpu, "popcnt");
  EXPECT_EQ(cpuRunsAvx2Backend(), all) << "the probe and `horopter devices` disagree";
  if (!avx2->available) {
    EXPECT_NE(avx2->unavailableReason.find(HOROPTER_AVX2_FEATURES), std::string::npos)
        << avx2->unavailableReason;
  }
}

TEST(CpuDispatch, NoScalarKernelIsAnAvx2One) {
  const Backend* avx2 = backendNamed("avx2");
  ASSERT_NE(avx2, nullptr);
  const KernelTable& s = *scalarBackend().kernels;
  const KernelTable& a = *avx2->kernels;
  EXPECT_NE(s.prefilterXSobel, a.prefilterXSobel);
  EXPECT_NE(s.matchBlocks, a.matchBlocks);
  EXPECT_NE(s.leftRightCheck, a.leftRightCheck);
  EXPECT_NE(s.filterSpeckles, a.filterSpeckles);
  EXPECT_NE(s.medianFilter, a.medianFilter);
  EXPECT_NE(s.horopterMask, a.horopterMask);
}

TEST(CpuDispatch, CpuBackendFollowsHoropterBackend) {
  const Backend* avx2 = backendNamed("avx2");
  ASSERT_NE(avx2, nullptr);
  const Backend& best = avx2->available ? *avx2 : scalarBackend();
  {
    const ScopedEnv forced("HOROPTER_BACKEND", "scalar");
    EXPECT_EQ(&cpuBackend(), &scalarBackend());
    EXPECT_TRUE(sameTable(*cpuBackend().kernels, *scalarBackend().kernels));
    EXPECT_EQ(&findBackend("auto"), &scalarBackend());
  }
  {
    const ScopedEnv unset("HOROPTER_BACKEND", nullptr);
    EXPECT_EQ(&cpuBackend(), &best) << cpuBackend().name;
  }
  {
    // A device backend forced: its CPU part still takes the best CPU backend.
    const ScopedEnv forced("HOROPTER_BACKEND", "opencl");
    EXPECT_EQ(&cpuBackend(), &best) << cpuBackend().name;
  }
  if (avx2->available) {
    const ScopedEnv forced("HOROPTER_BACKEND", "avx2");
    EXPECT_EQ(&cpuBackend(), avx2);
  }
}

}  // namespace
}  // namespace horopter::test
