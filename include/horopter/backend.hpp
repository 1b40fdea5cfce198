// Backends: one table of kernel entry points per implementation (scalar
// reference, later AVX2 and OpenCL), chosen by name at setup.
#pragma once

#include "horopter/export.hpp"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "horopter/image.hpp"
#include "horopter/stereo_params.hpp"

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

// The kernels a backend provides. Arguments reach these functions already
// validated by the public entry points in kernels.hpp (a RowRange reaches them
// resolved: 0 <= begin <= end <= height); every backend must give the scalar
// reference's result bit for bit, for any row range.
struct HOROPTER_API KernelTable {
  void (*prefilterXSobel)(const ConstImageView& src, int cap, const ImageView& filtered,
                          const ImageView& texture, RowRange rows);
  void (*matchBlocks)(const ConstImageView& left, const ConstImageView& right,
                      const ConstImageView& texture, const StereoParams& params,
                      const ImageView& disparity, const ImageView& winnerRight, RowRange rows);
  void (*leftRightCheck)(const ImageView& disparity, const ConstImageView& winnerRight,
                         const StereoParams& params, RowRange rows);
  void (*filterSpeckles)(const ImageView& disparity, const StereoParams& params);
  void (*medianFilter)(const ConstImageView& src, const ImageView& dst, int kernelSize,
                       int minValid, std::int16_t invalid, RowRange rows);
  void (*horopterMask)(const ConstImageView& disparity, std::span<const std::int16_t> thresholds,
                       std::int16_t invalid, const ImageView& mask, const ConstImageView& image,
                       const ImageView& segmented, RowRange rows);
};

struct HOROPTER_API Backend {
  std::string name;         // "scalar", "avx2", "opencl:0:0"...
  std::string description;  // one line for `horopter devices`
  bool available = false;
  std::string unavailableReason;  // why not, when !available
  KernelTable kernels{};
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
