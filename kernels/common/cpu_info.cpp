#include <fstream>
#include <string>
#include <string_view>
#include <thread>

#include "common/cpu_features.hpp"
#include "horopter/kernels/devices.hpp"

namespace horopter {

// The probe below must ask for every instruction set the AVX2 functions are
// compiled for: change both together.
static_assert(std::string_view(HOROPTER_AVX2_FEATURES) == "avx2,bmi,bmi2,popcnt",
              "HOROPTER_AVX2_FEATURES changed: update cpuRunsAvx2Backend() to probe the new list");

bool cpuRunsAvx2Backend() {
#if defined(__x86_64__) || defined(__i386__)
  // libgcc reports avx2 only when the OS saves the ymm state (OSXSAVE and
  // XCR0 bits 1-2), so that needs no check of its own; bmi, bmi2 and popcnt
  // use no new registers.
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("bmi") &&
         __builtin_cpu_supports("bmi2") && __builtin_cpu_supports("popcnt");
#else
  return false;
#endif
}

CpuInfo probeCpu() {
  CpuInfo info;
  info.model = "unknown";
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);) {
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) info.model = line.substr(colon + 2);
      break;
    }
  }
  info.hardwareThreads = std::thread::hardware_concurrency();
#if defined(__x86_64__) || defined(__i386__)
  __builtin_cpu_init();
  if (__builtin_cpu_supports("sse4.2")) info.features.push_back("sse4.2");
  if (__builtin_cpu_supports("popcnt")) info.features.push_back("popcnt");
  if (__builtin_cpu_supports("avx2")) info.features.push_back("avx2");
  if (__builtin_cpu_supports("bmi")) info.features.push_back("bmi");
  if (__builtin_cpu_supports("bmi2")) info.features.push_back("bmi2");
  if (__builtin_cpu_supports("fma")) info.features.push_back("fma");
  if (__builtin_cpu_supports("avx512f")) info.features.push_back("avx512f");
  if (__builtin_cpu_supports("avx512bw")) info.features.push_back("avx512bw");
  if (__builtin_cpu_supports("avx512vl")) info.features.push_back("avx512vl");
#endif
  return info;
}

}  // namespace horopter
