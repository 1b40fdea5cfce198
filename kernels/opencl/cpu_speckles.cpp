#include "opencl/cpu_speckles.hpp"

#include <atomic>

#include "common/cpu_backend.hpp"
#include "common/kernel_table.hpp"

namespace horopter::opencl {

namespace {
std::atomic<const Backend*> g_last{nullptr};
}  // namespace

const Backend& filterSpecklesOnCpu(const ImageView& disparity, const StereoParams& params) {
  const Backend& cpu = cpuBackend();
  cpu.kernels->filterSpeckles(disparity, params);
  g_last = &cpu;
  return cpu;
}

const Backend* lastSpeckleBackend() {
  return g_last;
}

}  // namespace horopter::opencl
