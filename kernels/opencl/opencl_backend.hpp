// The OpenCL entries of the backend registry, and how OpenCL names resolve.
//
// Names: "opencl" is the default device (the first GPU, else the first
// device, which on most machines is PoCL on the CPU); "opencl:N" is device N
// of `horopter devices`; any other name that is part of one device's name
// (case-insensitive) picks that device. The registry holds "opencl" and one
// "opencl:N" for every other device, so each device is enrolled once (the
// conformance test runs every entry). Without a device, "opencl" is still
// registered, unavailable, with the reason.
#pragma once

#include <string>
#include <vector>

#include "horopter/kernels/backend.hpp"

namespace horopter::opencl {

// The OpenCL backends, "opencl" first. Probes the platforms (cheap); the
// kernels are built on first use.
std::vector<Backend> makeBackends();

// The registry name of the backend that `wanted` means, when it is an
// OpenCL device's name ("opencl:N", a device-name substring); "" when it
// names no OpenCL device. Throws horopter::Error for "opencl:N" with N out
// of range, listing the devices.
std::string resolveBackendName(const std::string& wanted);

// The device index behind a registered OpenCL backend's name ("opencl" is
// the default device); -1 for any other name.
int deviceIndexOf(const std::string& backendName);

}  // namespace horopter::opencl
