// The OpenCL C API as Horopter uses it: version 1.2, errors as horopter::Error.
//
// The C API (CL/cl.h) rather than the C++ wrapper: the code needs only a few
// calls, the wrapper's exception/error-code modes and its version macros
// would be one more thing to configure, and the existing device listing
// already speaks the C API.
#pragma once

#define CL_TARGET_OPENCL_VERSION 120
#include <CL/cl.h>

#include <string>

namespace horopter::opencl {

// "CL_OUT_OF_RESOURCES" for -5, "error -9999" when unknown.
std::string errorName(cl_int err);

// Throws horopter::Error("OpenCL: <what> failed: <name>") unless err is CL_SUCCESS.
void check(cl_int err, const char* what);

// A string property of a device or platform, without its trailing NULs;
// "" when the query fails.
std::string deviceString(cl_device_id device, cl_device_info what);
std::string platformString(cl_platform_id platform, cl_platform_info what);

}  // namespace horopter::opencl
