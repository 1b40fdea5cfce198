// The OpenCL entries of a build without OpenCL: "opencl" is registered and
// unavailable, with the reason.
#include "opencl/opencl_backend.hpp"

#include "horopter/error.hpp"

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

}  // namespace horopter::opencl
