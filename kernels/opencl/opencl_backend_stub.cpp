// The OpenCL entries of a build without OpenCL: "opencl" is registered and
// unavailable, with the reason.
#include "opencl/opencl_backend.hpp"

#include "horopter/core/error.hpp"
#include "opencl/pipeline.hpp"

namespace horopter::opencl {

std::vector<Backend> makeBackends() {
  Backend b;
  b.name = "opencl";
  b.description = "OpenCL kernels on the default device (a GPU if present, else the CPU)";
  b.unavailableReason =
      "this build has no OpenCL support (install ocl-icd-opencl-dev and opencl-headers and "
      "configure with -DHOROPTER_WITH_OPENCL=ON)";
  return {b};
}

std::string resolveBackendName(const std::string& wanted) {
  if (wanted.rfind("opencl:", 0) == 0)
    throw Error("no OpenCL device '" + wanted + "': this build has no OpenCL support");
  return "";
}

int deviceIndexOf(const std::string&) {
  return -1;
}

struct Pipeline::Impl {};
void setInjectedEnqueueFailure(bool) {}

Pipeline::Pipeline(const std::string&, const StereoParams&, const MedianParams&, int) {
  throw Error(
      "this build has no OpenCL support (configure with -DHOROPTER_WITH_OPENCL=ON and the OpenCL "
      "headers and loader installed)");
}
Pipeline::~Pipeline() = default;
void Pipeline::submit(int, const ConstImageView&, const ConstImageView&, const StereoParams&,
                      Image&) {}
void Pipeline::wait(int, std::vector<OpenClStageTime>&) {}
const std::string& Pipeline::deviceName() const {
  static const std::string none = "none";
  return none;
}

}  // namespace horopter::opencl
