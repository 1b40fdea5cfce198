// Backends: one implementation of every kernel each (scalar reference, AVX2,
// OpenCL per device), chosen by name at setup.
#pragma once

#include "horopter/core/export.hpp"

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "horopter/core/image.hpp"
#include "horopter/kernels/stereo_params.hpp"

namespace horopter {

// The rows [begin, end) of the output that one kernel call writes. Inputs may
// be read outside them (a window's halo), so a frame split into stripes gives
// the same result as the whole frame. `all()` (end < 0) means every row.
struct HOROPTER_API RowRange {
  int begin = 0;
  int end = -1;
  static constexpr RowRange all() { return {0, -1}; }
  bool isAll() const { return end < 0; }
};

// The kernels' entry points: internal to the kernel layer
// (kernels/common/kernel_table.hpp), so that a new kernel does not change the
// ABI. Call them through the public functions of kernels.hpp.
struct KernelTable;

struct HOROPTER_API Backend {
  std::string name;         // "scalar", "avx2", "opencl:0:0"...
  std::string description;  // one line for `horopter devices`
  bool available = false;
  std::string unavailableReason;               // why not, when !available
  std::shared_ptr<const KernelTable> kernels;  // null when !available
};

// Every backend this build knows, available on this machine or not, best last.
HOROPTER_API const std::vector<const Backend*>& registeredBackends();

// The scalar reference: always available; the specification of every kernel.
HOROPTER_API const Backend& scalarBackend();

// Finds a backend by name. "auto" picks the best available one, unless the
// environment variable HOROPTER_BACKEND names one. Throws horopter::Error for
// an unknown name (listing the known ones) or an unavailable backend (with why).
HOROPTER_API const Backend& findBackend(const std::string& name);

}  // namespace horopter
