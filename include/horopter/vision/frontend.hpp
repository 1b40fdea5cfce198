// The per-frame stereo front end: prefilter, SAD matching, left-right check,
// speckle filter, hole-filling median, horopter mask. It owns its buffers
// (allocated when the frame size changes, reused otherwise) and runs the
// kernels of one backend. With threads > 1 each kernel runs as horizontal
// stripes on a pool of that many threads (the caller's included); the result
// is the one-thread result bit for bit. The speckle filter, which joins pixels
// across the whole frame, runs on one thread.
#pragma once

#include "horopter/core/export.hpp"

#include <cstdint>
#include <functional>
#include <memory>
#include <span>

#include "horopter/core/image.hpp"
#include "horopter/kernels/backend.hpp"
#include "horopter/kernels/stereo_params.hpp"
#include "horopter/vision/zone_search.hpp"

namespace horopter {

class ThreadPool;  // internal: engine/schedule/thread_pool.hpp

// Wall time of each stage of the last frame, in milliseconds.
struct HOROPTER_API FrontendTimings {
  double prefilter = 0, match = 0, cleanup = 0, median = 0, mask = 0;
  double total() const { return prefilter + match + cleanup + median + mask; }
};

// The front end's defaults, one set for every entry point: StereoFrontend's
// constructor here, Python's horopter.StereoMatcher and StereoBM_create, the
// C API's horopter_matcher_create (backend NULL, threads 0) and the CLI's
// --backend and --threads (`horopter disparity`, `profile`, `eval`; `run`
// takes all cores but one when frames are in flight, see cmd_run.cpp).
struct FrontendDefaults {
  // The best available backend (HOROPTER_BACKEND may force one): AVX2 where
  // the CPU has it, else the scalar reference; never OpenCL, which is chosen
  // by name. Every backend gives the reference's output bit for bit.
  static constexpr const char* backend = "auto";
  // 0: one stripe per hardware thread (resolveThreads). The output does not
  // depend on the thread count.
  static constexpr int threads = 0;
};

// A thread count as given (1..256), or for 0 the hardware's thread count (at
// least 1, at most 256). Throws horopter::Error for anything else.
HOROPTER_API int resolveThreads(int threads);

class HOROPTER_API StereoFrontend {
 public:
  // Validates the parameters and the thread count, 1..256 or 0 for every
  // hardware thread (throws horopter::Error). The defaults: FrontendDefaults.
  StereoFrontend(const StereoParams& stereo, const MedianParams& median,
                 const Backend& backend = findBackend(FrontendDefaults::backend),
                 int threads = FrontendDefaults::threads);
  ~StereoFrontend();
  StereoFrontend(StereoFrontend&&) noexcept;
  StereoFrontend& operator=(StereoFrontend&&) noexcept;

  // Rectified U8C1 pair in, final disparity (S16C1, 1/16 px) out: prefilter,
  // matching, left-right check, speckles, then the median when enabled.
  const Image& computeDisparity(const ConstImageView& left, const ConstImageView& right);
  // The same over another search range (zone-limited matching: see
  // zone_search.hpp): the chain runs with the range's minDisparity and
  // numDisparities (and the matcher checks the range's guardStep below it,
  // down to the configured minDisparity), and invalid pixels hold the
  // configured range's marker. The range must not start below the
  // configured minDisparity.
  const Image& computeDisparity(const ConstImageView& left, const ConstImageView& right,
                                SearchRange range);

  // Horopter mask of the last disparity: one threshold per column (1/16 px,
  // see geometry.hpp). When `image` (U8C1 or U8C3) is given, segmented()
  // receives it with the outside of the zone zeroed.
  void computeMask(std::span<const std::int16_t> thresholds, const ConstImageView& image = {});

  // False before the first computeDisparity (computeMask) and after one that
  // threw: the images below then hold no fresh result, whatever they contain.
  bool hasDisparity() const { return hasDisparity_; }
  bool hasMask() const { return hasMask_; }
  const Image& disparity() const;                           // final (after median)
  const Image& cleanedDisparity() const { return clean_; }  // before the median
  const Image& mask() const { return mask_; }
  const Image& segmented() const { return segmented_; }
  const FrontendTimings& timings() const { return timings_; }
  const StereoParams& stereoParams() const { return stereo_; }
  // Replaces the stereo parameters for the next frame; validated first (on a
  // bad value this throws horopter::Error and keeps the old ones).
  void setStereoParams(const StereoParams& stereo);
  const MedianParams& medianParams() const { return median_; }
  SearchRange lastRange() const { return lastRange_; }  // the last frame's search range
  const Backend& backend() const { return *backend_; }
  int threads() const;

 private:
  void allocate(int width, int height);
  // Runs fn over one stripe of rows per thread of the pool.
  void forEachStripe(int height, const std::function<void(RowRange)>& fn);

  StereoParams stereo_;
  MedianParams median_;
  const Backend* backend_;
  std::unique_ptr<ThreadPool> pool_;
  Image leftFiltered_, rightFiltered_, texture_;
  Image clean_, winnerRight_, median_out_;
  Image mask_, segmented_;
  FrontendTimings timings_;
  SearchRange lastRange_;
  bool hasDisparity_ = false, hasMask_ = false;
};

}  // namespace horopter
