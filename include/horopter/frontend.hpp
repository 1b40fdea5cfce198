// The per-frame stereo front end: prefilter, SAD matching, left-right check,
// speckle filter, hole-filling median, horopter mask. It owns its buffers
// (allocated when the frame size changes, reused otherwise) and runs the
// kernels of one backend; it starts no threads.
#pragma once

#include <cstdint>
#include <span>

#include "horopter/backend.hpp"
#include "horopter/image.hpp"
#include "horopter/stereo_params.hpp"

namespace horopter {

// Wall time of each stage of the last frame, in milliseconds.
struct FrontendTimings {
  double prefilter = 0, match = 0, cleanup = 0, median = 0, mask = 0;
  double total() const { return prefilter + match + cleanup + median + mask; }
};

class StereoFrontend {
 public:
  // Validates the parameters (throws horopter::Error).
  StereoFrontend(const StereoParams& stereo, const MedianParams& median,
                 const Backend& backend = scalarBackend());

  // Rectified U8C1 pair in, final disparity (S16C1, 1/16 px) out: prefilter,
  // matching, left-right check, speckles, then the median when enabled.
  const Image& computeDisparity(const ConstImageView& left, const ConstImageView& right);

  // Horopter mask of the last disparity: one threshold per column (1/16 px,
  // see geometry.hpp). When `image` (U8C1 or U8C3) is given, segmented()
  // receives it with the outside of the zone zeroed.
  void computeMask(std::span<const std::int16_t> thresholds, const ConstImageView& image = {});

  const Image& disparity() const;                           // final (after median)
  const Image& cleanedDisparity() const { return clean_; }  // before the median
  const Image& mask() const { return mask_; }
  const Image& segmented() const { return segmented_; }
  const FrontendTimings& timings() const { return timings_; }
  const StereoParams& stereoParams() const { return stereo_; }
  const MedianParams& medianParams() const { return median_; }
  const Backend& backend() const { return *backend_; }

 private:
  void allocate(int width, int height);

  StereoParams stereo_;
  MedianParams median_;
  const Backend* backend_;
  Image leftFiltered_, rightFiltered_, texture_;
  Image clean_, winnerRight_, median_out_;
  Image mask_, segmented_;
  FrontendTimings timings_;
};

}  // namespace horopter
