#include "opencl/device.hpp"

#include <utility>

#include "horopter/core/error.hpp"
#include "opencl/program_cache.hpp"

namespace horopter::opencl {

namespace {

struct Registry {
  std::vector<std::unique_ptr<Device>> owned;
  std::vector<Device*> list;
  std::string error;
};

Registry probe() {
  Registry reg;
  cl_uint platformCount = 0;
  const cl_int err = clGetPlatformIDs(0, nullptr, &platformCount);
  if (err != CL_SUCCESS || platformCount == 0) {
    reg.error =
        "no OpenCL platform (install pocl-opencl-icd for OpenCL on the CPU, or a GPU "
        "driver's ICD)";
    return reg;
  }
  std::vector<cl_platform_id> platforms(platformCount);
  clGetPlatformIDs(platformCount, platforms.data(), nullptr);
  for (cl_platform_id platform : platforms) {
    cl_uint count = 0;
    if (clGetDeviceIDs(platform, CL_DEVICE_TYPE_ALL, 0, nullptr, &count) != CL_SUCCESS) continue;
    std::vector<cl_device_id> ids(count);
    clGetDeviceIDs(platform, CL_DEVICE_TYPE_ALL, count, ids.data(), nullptr);
    for (cl_device_id id : ids) {
      DeviceDesc d;
      d.index = static_cast<int>(reg.list.size());
      d.platform = platform;
      d.id = id;
      d.name = deviceString(id, CL_DEVICE_NAME);
      d.version = deviceString(id, CL_DEVICE_VERSION);
      d.driverVersion = deviceString(id, CL_DRIVER_VERSION);
      d.platformName = platformString(platform, CL_PLATFORM_NAME);
      cl_device_type type = 0;
      clGetDeviceInfo(id, CL_DEVICE_TYPE, sizeof(type), &type, nullptr);
      d.gpu = (type & CL_DEVICE_TYPE_GPU) != 0;
      cl_uint units = 1;
      clGetDeviceInfo(id, CL_DEVICE_MAX_COMPUTE_UNITS, sizeof(units), &units, nullptr);
      d.computeUnits = units > 0 ? units : 1;
      cl_ulong maxAlloc = 0;
      clGetDeviceInfo(id, CL_DEVICE_MAX_MEM_ALLOC_SIZE, sizeof(maxAlloc), &maxAlloc, nullptr);
      d.maxAlloc = maxAlloc;
      reg.owned.push_back(std::make_unique<Device>(std::move(d)));
      reg.list.push_back(reg.owned.back().get());
    }
  }
  if (reg.list.empty()) reg.error = "the OpenCL platforms here offer no device";
  return reg;
}

// Never destroyed: releasing OpenCL objects from static destructors races
// the ICD loader's and the driver's own teardown at exit.
const Registry& registry() {
  static const Registry* reg = new Registry(probe());
  return *reg;
}

}  // namespace

Device::Device(DeviceDesc desc) : desc_(std::move(desc)) {}

Device::~Device() {
  for (auto& [options, program] : variants_)
    if (program) clReleaseProgram(program);
  if (program_) clReleaseProgram(program_);
  if (queue_) clReleaseCommandQueue(queue_);
  if (context_) clReleaseContext(context_);
}

cl_context Device::context() {
  const std::lock_guard<std::mutex> lock(setup_);
  if (!context_) {
    cl_int err = CL_SUCCESS;
    const cl_context_properties props[] = {
        CL_CONTEXT_PLATFORM, reinterpret_cast<cl_context_properties>(desc_.platform), 0};
    context_ = clCreateContext(props, 1, &desc_.id, nullptr, nullptr, &err);
    check(err, ("creating a context on " + desc_.name).c_str());
  }
  return context_;
}

cl_command_queue Device::queue() {
  cl_context ctx = context();
  const std::lock_guard<std::mutex> lock(setup_);
  if (!queue_) {
    cl_int err = CL_SUCCESS;
    queue_ = clCreateCommandQueue(ctx, desc_.id, CL_QUEUE_PROFILING_ENABLE, &err);
    check(err, "creating a command queue");
  }
  return queue_;
}

cl_program Device::program() {
  cl_context ctx = context();
  const std::lock_guard<std::mutex> lock(setup_);
  // An injected failure goes through the real compiler (an #error in the
  // sources), even when the program was built before, and is not cached.
  if (injectedBuildFailure()) buildProgram(desc_, ctx);
  if (!program_) {
    const BuiltProgram built = buildProgram(desc_, ctx);
    program_ = built.program;
    origin_ = built.origin;
  }
  return program_;
}

cl_program Device::program(const std::string& extraOptions) {
  if (extraOptions.empty()) return program();
  cl_context ctx = context();
  const std::lock_guard<std::mutex> lock(setup_);
  cl_program& built = variants_[extraOptions];
  if (!built) built = buildProgram(desc_, ctx, extraOptions).program;
  return built;
}

ProgramOrigin Device::programOrigin() {
  program();
  const std::lock_guard<std::mutex> lock(setup_);
  return origin_;
}

const std::vector<Device*>& devices() {
  return registry().list;
}

const std::string& probeError() {
  return registry().error;
}

cl_command_queue createQueue(Device& device) {
  cl_int err = CL_SUCCESS;
  cl_command_queue q =
      clCreateCommandQueue(device.context(), device.desc().id, CL_QUEUE_PROFILING_ENABLE, &err);
  check(err, "creating a command queue");
  return q;
}

KernelHandle createKernel(Device& device, const char* name) {
  cl_int err = CL_SUCCESS;
  cl_kernel k = clCreateKernel(device.program(), name, &err);
  check(err, (std::string("creating kernel ") + name).c_str());
  return KernelHandle(k);
}

}  // namespace horopter::opencl
