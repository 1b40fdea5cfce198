// Lists OpenCL platforms and devices (through the ICD loader). Without
// HOROPTER_WITH_OPENCL it reports that OpenCL was not built.
#include <string>
#include <vector>

#include "horopter/kernels/devices.hpp"

#ifdef HOROPTER_HAVE_OPENCL
#include "opencl/cl_api.hpp"
#endif

namespace horopter {

#ifdef HOROPTER_HAVE_OPENCL
namespace {

using opencl::deviceString;
using opencl::platformString;

std::string typeName(cl_device_type type) {
  if (type & CL_DEVICE_TYPE_GPU) return "gpu";
  if (type & CL_DEVICE_TYPE_CPU) return "cpu";
  if (type & CL_DEVICE_TYPE_ACCELERATOR) return "accelerator";
  return "other";
}

}  // namespace
#endif

OpenClReport probeOpenCl() {
  OpenClReport report;
#ifdef HOROPTER_HAVE_OPENCL
  report.built = true;
  cl_uint platformCount = 0;
  cl_int err = clGetPlatformIDs(0, nullptr, &platformCount);
  if (err != CL_SUCCESS || platformCount == 0) {
    report.error = err == CL_SUCCESS ? "no OpenCL platform installed (install pocl-opencl-icd for "
                                       "OpenCL on the CPU, or a GPU driver's ICD)"
                                     : "clGetPlatformIDs failed with error " + std::to_string(err) +
                                           " (no ICD installed?)";
    return report;
  }
  std::vector<cl_platform_id> platforms(platformCount);
  clGetPlatformIDs(platformCount, platforms.data(), nullptr);
  for (cl_uint p = 0; p < platformCount; ++p) {
    cl_uint deviceCount = 0;
    if (clGetDeviceIDs(platforms[p], CL_DEVICE_TYPE_ALL, 0, nullptr, &deviceCount) != CL_SUCCESS)
      continue;
    std::vector<cl_device_id> devices(deviceCount);
    clGetDeviceIDs(platforms[p], CL_DEVICE_TYPE_ALL, deviceCount, devices.data(), nullptr);
    for (cl_uint d = 0; d < deviceCount; ++d) {
      OpenClDevice dev;
      dev.platform = static_cast<int>(p);
      dev.device = static_cast<int>(d);
      dev.platformName = platformString(platforms[p], CL_PLATFORM_NAME);
      dev.deviceName = deviceString(devices[d], CL_DEVICE_NAME);
      dev.version = deviceString(devices[d], CL_DEVICE_VERSION);
      cl_device_type type = 0;
      clGetDeviceInfo(devices[d], CL_DEVICE_TYPE, sizeof(type), &type, nullptr);
      dev.type = typeName(type);
      cl_uint units = 0;
      clGetDeviceInfo(devices[d], CL_DEVICE_MAX_COMPUTE_UNITS, sizeof(units), &units, nullptr);
      dev.computeUnits = units;
      cl_ulong mem = 0;
      clGetDeviceInfo(devices[d], CL_DEVICE_GLOBAL_MEM_SIZE, sizeof(mem), &mem, nullptr);
      dev.globalMemBytes = mem;
      report.devices.push_back(dev);
    }
  }
#else
  report.error = "this build has no OpenCL support (configure with -DHOROPTER_WITH_OPENCL=ON)";
#endif
  return report;
}

}  // namespace horopter
