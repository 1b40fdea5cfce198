#include "opencl/cl_api.hpp"

#include <CL/cl_ext.h>

#include "horopter/core/error.hpp"

namespace horopter::opencl {

std::string errorName(cl_int err) {
  switch (err) {
#define HOROPTER_CL_ERROR(name) \
  case name:                    \
    return #name;
    HOROPTER_CL_ERROR(CL_SUCCESS)
    HOROPTER_CL_ERROR(CL_DEVICE_NOT_FOUND)
    HOROPTER_CL_ERROR(CL_DEVICE_NOT_AVAILABLE)
    HOROPTER_CL_ERROR(CL_COMPILER_NOT_AVAILABLE)
    HOROPTER_CL_ERROR(CL_MEM_OBJECT_ALLOCATION_FAILURE)
    HOROPTER_CL_ERROR(CL_OUT_OF_RESOURCES)
    HOROPTER_CL_ERROR(CL_OUT_OF_HOST_MEMORY)
    HOROPTER_CL_ERROR(CL_PROFILING_INFO_NOT_AVAILABLE)
    HOROPTER_CL_ERROR(CL_MEM_COPY_OVERLAP)
    HOROPTER_CL_ERROR(CL_BUILD_PROGRAM_FAILURE)
    HOROPTER_CL_ERROR(CL_MAP_FAILURE)
    HOROPTER_CL_ERROR(CL_EXEC_STATUS_ERROR_FOR_EVENTS_IN_WAIT_LIST)
    HOROPTER_CL_ERROR(CL_COMPILE_PROGRAM_FAILURE)
    HOROPTER_CL_ERROR(CL_LINK_PROGRAM_FAILURE)
    HOROPTER_CL_ERROR(CL_INVALID_VALUE)
    HOROPTER_CL_ERROR(CL_INVALID_DEVICE)
    HOROPTER_CL_ERROR(CL_INVALID_CONTEXT)
    HOROPTER_CL_ERROR(CL_INVALID_COMMAND_QUEUE)
    HOROPTER_CL_ERROR(CL_INVALID_MEM_OBJECT)
    HOROPTER_CL_ERROR(CL_INVALID_BINARY)
    HOROPTER_CL_ERROR(CL_INVALID_BUILD_OPTIONS)
    HOROPTER_CL_ERROR(CL_INVALID_PROGRAM)
    HOROPTER_CL_ERROR(CL_INVALID_PROGRAM_EXECUTABLE)
    HOROPTER_CL_ERROR(CL_INVALID_KERNEL_NAME)
    HOROPTER_CL_ERROR(CL_INVALID_KERNEL)
    HOROPTER_CL_ERROR(CL_INVALID_ARG_INDEX)
    HOROPTER_CL_ERROR(CL_INVALID_ARG_VALUE)
    HOROPTER_CL_ERROR(CL_INVALID_ARG_SIZE)
    HOROPTER_CL_ERROR(CL_INVALID_KERNEL_ARGS)
    HOROPTER_CL_ERROR(CL_INVALID_WORK_DIMENSION)
    HOROPTER_CL_ERROR(CL_INVALID_WORK_GROUP_SIZE)
    HOROPTER_CL_ERROR(CL_INVALID_WORK_ITEM_SIZE)
    HOROPTER_CL_ERROR(CL_INVALID_GLOBAL_OFFSET)
    HOROPTER_CL_ERROR(CL_INVALID_EVENT_WAIT_LIST)
    HOROPTER_CL_ERROR(CL_INVALID_EVENT)
    HOROPTER_CL_ERROR(CL_INVALID_OPERATION)
    HOROPTER_CL_ERROR(CL_INVALID_BUFFER_SIZE)
    HOROPTER_CL_ERROR(CL_INVALID_GLOBAL_WORK_SIZE)
    HOROPTER_CL_ERROR(CL_PLATFORM_NOT_FOUND_KHR)
#undef HOROPTER_CL_ERROR
    default:
      return "error " + std::to_string(err);
  }
}

void check(cl_int err, const char* what) {
  if (err != CL_SUCCESS) throw Error(std::string("OpenCL: ") + what + " failed: " + errorName(err));
}

std::string deviceString(cl_device_id device, cl_device_info what) {
  size_t size = 0;
  if (clGetDeviceInfo(device, what, 0, nullptr, &size) != CL_SUCCESS || size == 0) return "";
  std::string s(size, '\0');
  clGetDeviceInfo(device, what, size, s.data(), nullptr);
  while (!s.empty() && s.back() == '\0')
    s.pop_back();
  return s;
}

std::string platformString(cl_platform_id platform, cl_platform_info what) {
  size_t size = 0;
  if (clGetPlatformInfo(platform, what, 0, nullptr, &size) != CL_SUCCESS || size == 0) return "";
  std::string s(size, '\0');
  clGetPlatformInfo(platform, what, size, s.data(), nullptr);
  while (!s.empty() && s.back() == '\0')
    s.pop_back();
  return s;
}

}  // namespace horopter::opencl
