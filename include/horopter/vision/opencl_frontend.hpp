// The stereo front end on an OpenCL device, asynchronous.
//
// Device buffers are allocated once per frame size and reused; each frame's
// upload, kernels and download are enqueued on one in-order queue with
// events, so that submit() returns at once and several frames (up to
// `inFlight`) can be in flight. wait() returns a frame's disparity;
// computeDisparity() is submit + wait. The result is the scalar reference's
// bit for bit (the speckle filter runs on the CPU between the left-right
// check and the median, in wait(); when speckleWindowSize is 0 the whole
// chain stays on the device).
//
// Fallback: if the device cannot be used (no platform, a failed program
// build, a failed enqueue, a device that goes away), a warning goes to
// stderr and this frame and every later one run on the best CPU backend
// (scalar when HOROPTER_BACKEND=scalar), with the same results; no frame is
// lost or reordered. A device name that names nothing is an error
// (horopter::Error), not a fallback.
#pragma once

#include "horopter/core/export.hpp"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "horopter/core/image.hpp"
#include "horopter/kernels/backend.hpp"
#include "horopter/kernels/stereo_params.hpp"
#include "horopter/vision/zone_search.hpp"

namespace horopter {

// Device time of one stage of a frame (upload, a kernel, download), from
// OpenCL profiling events; CPU stages (the speckle filter) in wall time.
struct HOROPTER_API OpenClStageTime {
  std::string stage;
  double ms = 0;
  bool onDevice = true;
};

namespace opencl {
class Pipeline;
}

class HOROPTER_API OpenClFrontend {
 public:
  using Ticket = std::uint64_t;

  // `device`: "opencl" (a GPU if present, else the CPU device), "opencl:N" or
  // part of a device's name, as findBackend(). `inFlight`: frames that may
  // be pending at once, 1..16. `cpuThreads`: threads of the CPU fallback.
  OpenClFrontend(const StereoParams& stereo, const MedianParams& median,
                 const std::string& device = "opencl", int inFlight = 2, int cpuThreads = 1);
  ~OpenClFrontend();
  OpenClFrontend(const OpenClFrontend&) = delete;
  OpenClFrontend& operator=(const OpenClFrontend&) = delete;

  // Enqueues a rectified U8C1 pair and returns at once. The views must stay
  // valid and unchanged until wait() for this ticket returns. With
  // `inFlight` frames pending, the oldest is completed first.
  Ticket submit(const ConstImageView& left, const ConstImageView& right);
  // The same over another search range (zone-limited matching), as
  // StereoFrontend::computeDisparity with a range.
  Ticket submit(const ConstImageView& left, const ConstImageView& right, SearchRange range);
  // Blocks until the frame is done: its final disparity (S16C1, 1/16 px),
  // valid until `inFlight` more frames have been submitted.
  const Image& wait(Ticket ticket);
  // submit + wait.
  const Image& computeDisparity(const ConstImageView& left, const ConstImageView& right);
  const Image& computeDisparity(const ConstImageView& left, const ConstImageView& right,
                                SearchRange range);

  // Stage times of the last frame waited for on the device (empty on the CPU).
  const std::vector<OpenClStageTime>& profile() const { return profile_; }
  // True once the front end has fallen back to the CPU, and why.
  bool onCpu() const { return cpu_ != nullptr; }
  const std::string& fallbackReason() const { return fallbackReason_; }
  // The OpenCL device's name, or the CPU backend's after a fallback.
  const std::string& deviceName() const { return deviceName_; }

 private:
  struct Slot;
  void fallBack(const std::string& why);
  void computeOnCpu(Slot& slot);
  void finish(Slot& slot);
  Slot& slotOf(Ticket ticket);

  StereoParams stereo_;
  MedianParams median_;
  int cpuThreads_;
  std::unique_ptr<opencl::Pipeline> pipeline_;
  std::vector<std::unique_ptr<Slot>> slots_;
  Ticket next_ = 0;
  class CpuPath;
  std::unique_ptr<CpuPath> cpu_;
  std::string fallbackReason_, deviceName_;
  std::vector<OpenClStageTime> profile_;
};

}  // namespace horopter
