// The table of backends. A new backend adds one entry here, and the
// conformance test and the benches pick it up from this list.
#include <cstdlib>
#include <memory>
#include <string>

#include "common/cpu_backend.hpp"
#include "common/cpu_features.hpp"
#include "common/kernel_table.hpp"
#include "horopter/core/error.hpp"
#include "horopter/kernels/backend.hpp"
#include "horopter_mask/horopter_mask.hpp"
#include "median/median.hpp"
#include "occlusion/occlusion.hpp"
#include "opencl/opencl_backend.hpp"
#include "prefilter/prefilter.hpp"
#include "sad/sad.hpp"

namespace horopter {

namespace {

Backend makeScalar() {
  Backend b;
  b.name = "scalar";
  b.description = "portable C++ reference (the specification)";
  b.available = true;
  KernelTable t;
  t.prefilterXSobel = scalar::prefilterXSobel;
  t.prefilterNormalized = scalar::prefilterNormalized;
  t.matchBlocks = scalar::matchBlocks;
  t.leftRightCheck = scalar::leftRightCheck;
  t.filterSpeckles = scalar::filterSpeckles;
  t.medianFilter = scalar::medianFilter;
  t.horopterMask = scalar::horopterMask;
  b.kernels = std::make_shared<const KernelTable>(t);
  return b;
}

// AVX2 kernels where they exist.
Backend makeAvx2() {
  Backend b;
  b.name = "avx2";
  b.description = "hand-written AVX2 kernels (x86-64 CPUs with AVX2)";
  b.available = cpuRunsAvx2Backend();
  if (!b.available) b.unavailableReason = "this CPU or its OS lacks one of " HOROPTER_AVX2_FEATURES;
  KernelTable t;
  t.prefilterXSobel = avx2::prefilterXSobel;
  t.prefilterNormalized = avx2::prefilterNormalized;
  t.matchBlocks = avx2::matchBlocks;
  t.leftRightCheck = avx2::leftRightCheck;
  t.filterSpeckles = avx2::filterSpeckles;
  t.medianFilter = avx2::medianFilter;
  t.horopterMask = avx2::horopterMask;
  b.kernels = std::make_shared<const KernelTable>(t);
  return b;
}

const Backend& avx2Backend() {
  static const Backend avx2 = makeAvx2();
  return avx2;
}

// The name HOROPTER_BACKEND gives, or "" when unset.
std::string forcedName() {
  const char* forced = std::getenv("HOROPTER_BACKEND");
  return forced != nullptr ? std::string(forced) : std::string();
}

std::string knownNames() {
  std::string names = "auto";
  for (const Backend* b : registeredBackends())
    names += ", " + b->name;
  return names;
}

}  // namespace

const Backend& scalarBackend() {
  static const Backend scalar = makeScalar();
  return scalar;
}

const Backend& cpuBackend() {
  const Backend& avx2 = avx2Backend();
  if (forcedName() == "scalar" || !avx2.available) return scalarBackend();
  return avx2;
}

const std::vector<const Backend*>& registeredBackends() {
  // OpenCL entries sit before the CPU SIMD ones, so that `auto` never picks
  // a device path on its own: `--backend opencl` asks for it.
  static const std::vector<Backend> opencl = opencl::makeBackends();
  static const std::vector<const Backend*> all = [] {
    std::vector<const Backend*> list = {&scalarBackend()};
    for (const Backend& b : opencl)
      list.push_back(&b);
    list.push_back(&avx2Backend());
    return list;
  }();
  return all;
}

const Backend& findBackend(const std::string& name) {
  std::string wanted = name;
  if (wanted == "auto") {
    const std::string forced = forcedName();
    if (!forced.empty() && forced != "auto") wanted = forced;
  }
  if (wanted == "auto") {
    const Backend* best = &scalarBackend();
    for (const Backend* b : registeredBackends()) {
      if (b->available) best = b;
    }
    return *best;
  }
  for (const Backend* b : registeredBackends()) {
    if (b->name != wanted) continue;
    if (!b->available)
      throw Error("backend '" + wanted +
                  "' is not available on this machine: " + b->unavailableReason);
    return *b;
  }
  // "opencl:N" or part of an OpenCL device's name.
  const std::string device = opencl::resolveBackendName(wanted);
  if (!device.empty()) return findBackend(device);
  throw Error("unknown backend '" + wanted + "': use one of " + knownNames() +
              ", opencl:N or part of an OpenCL device's name (see `horopter devices`)");
}

}  // namespace horopter
