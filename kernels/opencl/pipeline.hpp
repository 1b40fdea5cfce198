// The per-frame chain on one OpenCL device, for the asynchronous front end
// (include/horopter/vision/opencl_frontend.hpp): one in-order queue, its own
// cl_kernel objects, and per slot (a frame in flight) the device buffers,
// reused from frame to frame. Every OpenCL failure is a horopter::Error.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "horopter/core/image.hpp"
#include "horopter/kernels/kernels.hpp"
#include "horopter/kernels/stereo_params.hpp"
#include "horopter/vision/opencl_frontend.hpp"

namespace horopter::opencl {

class Pipeline {
 public:
  // `backendName`: a registered OpenCL backend's name ("opencl", "opencl:N").
  Pipeline(const std::string& backendName, const StereoParams& stereo, const MedianParams& median,
           int slots);
  ~Pipeline();
  Pipeline(const Pipeline&) = delete;
  Pipeline& operator=(const Pipeline&) = delete;

  // Enqueues the frame into `slot` without waiting; `out` (the frame's
  // size, S16C1) receives the final disparity by wait(slot). `stereo`: the
  // constructor's parameters, or the same over another search range (its
  // invalid marker is then that range's); `guard`: the matcher's check
  // below that range (kernels.hpp).
  void submit(int slot, const ConstImageView& left, const ConstImageView& right,
              const StereoParams& stereo, const BelowRangeGuard& guard, Image& out);
  // Completes the slot's frame (the CPU speckle filter and the median when
  // speckles are on) and fills `times` with its stage times.
  void wait(int slot, std::vector<OpenClStageTime>& times);
  const std::string& deviceName() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Test hook: while set, Pipeline::submit fails as a failed enqueue would.
void setInjectedEnqueueFailure(bool on);

}  // namespace horopter::opencl
