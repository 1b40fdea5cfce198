// OpenCL devices: the flat list of every device of every platform (index N
// is `opencl:N`), each with a context, an in-order profiling queue and the
// front end's program, built once per process on first use.
#pragma once

#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "opencl/cl_api.hpp"

namespace horopter::opencl {

struct DeviceDesc {
  int index = 0;  // position in devices(): the N of opencl:N
  cl_platform_id platform = nullptr;
  cl_device_id id = nullptr;
  std::string name, platformName, version, driverVersion;
  bool gpu = false;
  unsigned computeUnits = 1;
  unsigned long long maxAlloc = 0;  // CL_DEVICE_MAX_MEM_ALLOC_SIZE, bytes
};

// Where a program came from, for tests and logs.
enum class ProgramOrigin { Source, DiskCache, RebuiltAfterBadCacheEntry };

class Device {
 public:
  explicit Device(DeviceDesc desc);
  ~Device();
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;

  const DeviceDesc& desc() const { return desc_; }
  // Created on first use; thread-safe. Throw horopter::Error on failure.
  cl_context context();
  cl_command_queue queue();  // the synchronous kernel path's queue
  cl_program program();      // every front-end kernel, built once
  // The same sources built with extra options (tiled_variant.hpp), once
  // per distinct options; "" is program().
  cl_program program(const std::string& extraOptions);
  ProgramOrigin programOrigin();
  // Held by the synchronous kernel path for a whole call: cl_kernel
  // arguments and the shared buffers are per-object state.
  std::mutex& callMutex() { return call_; }

 private:
  DeviceDesc desc_;
  std::mutex setup_, call_;
  cl_context context_ = nullptr;
  cl_command_queue queue_ = nullptr;
  cl_program program_ = nullptr;
  std::map<std::string, cl_program> variants_;  // program(extraOptions)
  ProgramOrigin origin_ = ProgramOrigin::Source;
};

// Every device of every platform, in platform order; empty when there is no
// platform. `probeError()` says why when the list is empty.
const std::vector<Device*>& devices();
const std::string& probeError();

// A new in-order command queue with profiling enabled.
cl_command_queue createQueue(Device& device);

// A cl_kernel owned by a unique_ptr-like handle.
struct KernelDeleter {
  void operator()(cl_kernel k) const { clReleaseKernel(k); }
};
using KernelHandle = std::unique_ptr<std::remove_pointer_t<cl_kernel>, KernelDeleter>;
KernelHandle createKernel(Device& device, const char* name);

}  // namespace horopter::opencl
