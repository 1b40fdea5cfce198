#include "horopter/vision/opencl_frontend.hpp"

#include <algorithm>
#include <iostream>

#include "common/cpu_backend.hpp"
#include "horopter/core/error.hpp"
#include "horopter/vision/frontend.hpp"
#include "opencl/opencl_backend.hpp"
#include "opencl/pipeline.hpp"

namespace horopter {

namespace {

// The registered OpenCL backend `device` names; throws horopter::Error for a
// name that names nothing (a typo must not pass for a missing GPU).
const Backend& openclBackendNamed(const std::string& device) {
  // "opencl:N" (N is checked) or a part of a device's name; "" for nothing.
  const std::string name = device == "opencl" ? device : opencl::resolveBackendName(device);
  for (const Backend* b : registeredBackends())
    if (!name.empty() && b->name == name) return *b;
  throw Error("'" + device +
              "' names no OpenCL device: use opencl, opencl:N or part of a device's name (see "
              "`horopter devices`)");
}

}  // namespace

// The CPU front end taken after a fallback.
class OpenClFrontend::CpuPath {
 public:
  CpuPath(const StereoParams& stereo, const MedianParams& median, int threads)
      : frontend(stereo, median, cpuBackend(), threads) {}
  StereoFrontend frontend;
};

struct OpenClFrontend::Slot {
  Ticket ticket = 0;
  bool used = false, done = false, onDevice = false;
  ConstImageView left, right;
  SearchRange range;
  Image out;
};

OpenClFrontend::OpenClFrontend(const StereoParams& stereo, const MedianParams& median,
                               const std::string& device, int inFlight, int cpuThreads)
    : stereo_(stereo), median_(median), cpuThreads_(cpuThreads) {
  validate(stereo_);
  validate(median_);
  if (inFlight < 1 || inFlight > 16)
    throw Error("inFlight must be within 1..16 frames, got " + std::to_string(inFlight));
  if (cpuThreads < 1 || cpuThreads > 256)
    throw Error("cpuThreads must be within 1..256, got " + std::to_string(cpuThreads));
  for (int i = 0; i < inFlight; ++i)
    slots_.push_back(std::make_unique<Slot>());
  const Backend& backend = openclBackendNamed(device);
  if (!backend.available) {
    fallBack("OpenCL backend '" + backend.name +
             "' is not available: " + backend.unavailableReason);
    return;
  }
  try {
    pipeline_ = std::make_unique<opencl::Pipeline>(backend.name, stereo_, median_, inFlight);
    deviceName_ = pipeline_->deviceName();
  } catch (const Error& e) {
    fallBack(e.what());
  }
}

OpenClFrontend::~OpenClFrontend() = default;

void OpenClFrontend::fallBack(const std::string& why) {
  if (cpu_) return;
  // Drains (or abandons) whatever the device still had, so that nothing it
  // writes can land in a slot the CPU is filling.
  pipeline_.reset();
  cpu_ = std::make_unique<CpuPath>(stereo_, median_, cpuThreads_);
  fallbackReason_ = why;
  deviceName_ = cpu_->frontend.backend().name;
  std::cerr << "horopter: warning: " << why << "\nhoropter: warning: continuing on the CPU ("
            << deviceName_ << " backend)\n";
}

void OpenClFrontend::computeOnCpu(Slot& slot) {
  const Image& d = cpu_->frontend.computeDisparity(slot.left, slot.right, slot.range);
  if (slot.out.width() != d.width() || slot.out.height() != d.height())
    slot.out = Image(d.width(), d.height(), PixelType::S16C1);
  for (int y = 0; y < d.height(); ++y)
    std::copy_n(d.row<std::int16_t>(y), d.width(), slot.out.row<std::int16_t>(y));
  slot.onDevice = false;
  slot.done = true;
}

OpenClFrontend::Slot& OpenClFrontend::slotOf(Ticket ticket) {
  Slot& slot = *slots_[ticket % slots_.size()];
  if (!slot.used || slot.ticket != ticket)
    throw Error("frame " + std::to_string(ticket) +
                " is not pending (already reused: at most inFlight frames are kept)");
  return slot;
}

OpenClFrontend::Ticket OpenClFrontend::submit(const ConstImageView& left,
                                              const ConstImageView& right) {
  return submit(left, right, fullRange(stereo_));
}

OpenClFrontend::Ticket OpenClFrontend::submit(const ConstImageView& left,
                                              const ConstImageView& right, SearchRange range) {
  checkSearchRange(stereo_, range);
  checkView(left, PixelType::U8C1, "left image");
  checkView(right, PixelType::U8C1, "right image");
  checkSameSize(left, "left image", right, "right image");
  if (left.width < stereo_.blockSize || left.height < stereo_.blockSize)
    throw Error("image is smaller than the matching block: use a smaller blockSize");
  const Ticket ticket = next_;
  Slot& slot = *slots_[ticket % slots_.size()];
  if (slot.used && !slot.done) wait(slot.ticket);  // the oldest frame first
  ++next_;
  slot.ticket = ticket;
  slot.used = true;
  slot.done = false;
  slot.left = left;
  slot.right = right;
  slot.range = range;
  if (slot.out.width() != left.width || slot.out.height() != left.height)
    slot.out = Image(left.width, left.height, PixelType::S16C1);
  if (!cpu_) {
    try {
      pipeline_->submit(static_cast<int>(ticket % slots_.size()), left, right,
                        withRange(stereo_, range), guardBelow(stereo_, range), slot.out);
      slot.onDevice = true;
      return ticket;
    } catch (const Error& e) {
      fallBack(e.what());
    }
  }
  computeOnCpu(slot);
  return ticket;
}

const Image& OpenClFrontend::wait(Ticket ticket) {
  Slot& slot = slotOf(ticket);
  if (slot.done) return slot.out;
  if (!cpu_) {
    try {
      pipeline_->wait(static_cast<int>(ticket % slots_.size()), profile_);
      finish(slot);
      return slot.out;
    } catch (const Error& e) {
      fallBack(e.what());
    }
  }
  // Submitted to a device that failed since: redo it on the CPU, in order.
  profile_.clear();
  computeOnCpu(slot);
  return slot.out;
}

// The device ran the chain with the slot's range: its invalid pixels carry
// that range's marker, rewritten here as the configured range's (the CPU
// path's front end does the same before its median).
void OpenClFrontend::finish(Slot& slot) {
  slot.done = true;
  restoreInvalidMarker(slot.out.view(), stereo_, slot.range);
}

const Image& OpenClFrontend::computeDisparity(const ConstImageView& left,
                                              const ConstImageView& right) {
  return wait(submit(left, right));
}

const Image& OpenClFrontend::computeDisparity(const ConstImageView& left,
                                              const ConstImageView& right, SearchRange range) {
  return wait(submit(left, right, range));
}

}  // namespace horopter
