// The kernels a backend provides: one function pointer per kernel. Internal
// to the kernel layer, so that adding a kernel does not change libhoropter's ABI.
#pragma once

#include <cstdint>
#include <span>

#include "horopter/core/image.hpp"
#include "horopter/kernels/backend.hpp"
#include "horopter/kernels/kernels.hpp"
#include "horopter/kernels/stereo_params.hpp"

namespace horopter {

// The kernels a backend provides. Arguments reach these functions already
// validated by the public entry points in kernels.hpp (a RowRange reaches them
// resolved: 0 <= begin <= end <= height); every backend must give the scalar
// reference's result bit for bit, for any row range.
struct KernelTable {
  void (*prefilterXSobel)(const ConstImageView& src, int cap, const ImageView& filtered,
                          const ImageView& texture, RowRange rows);
  void (*prefilterNormalized)(const ConstImageView& src, int cap, int size,
                              const ImageView& filtered, const ImageView& texture, RowRange rows);
  void (*matchBlocks)(const ConstImageView& left, const ConstImageView& right,
                      const ConstImageView& texture, const StereoParams& params,
                      const BelowRangeGuard& guard, const ImageView& disparity,
                      const ImageView& winnerRight, RowRange rows);
  void (*leftRightCheck)(const ImageView& disparity, const ConstImageView& winnerRight,
                         const StereoParams& params, RowRange rows);
  void (*filterSpeckles)(const ImageView& disparity, const StereoParams& params);
  void (*medianFilter)(const ConstImageView& src, const ImageView& dst, int kernelSize,
                       int minValid, std::int16_t invalid, RowRange rows);
  void (*horopterMask)(const ConstImageView& disparity, std::span<const std::int16_t> thresholds,
                       std::int16_t invalid, const ImageView& mask, const ConstImageView& image,
                       const ImageView& segmented, RowRange rows);
};

}  // namespace horopter
