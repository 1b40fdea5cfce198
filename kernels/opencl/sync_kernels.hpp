// The synchronous kernel table of one OpenCL device: each entry uploads the
// rows it reads, runs the kernel and downloads the rows it writes before it
// returns. Calls on one device are serialised (one queue, one set of
// cl_kernel objects and buffers per device); the speckle filter runs on the
// CPU (opencl/cpu_speckles.hpp), as it joins pixels across the whole frame.
#pragma once

#include "common/kernel_table.hpp"

namespace horopter::opencl {

// Devices beyond this many are listed by `horopter devices` but get no backend.
constexpr int kMaxBackendDevices = 8;

// The table for devices()[index], index < kMaxBackendDevices.
KernelTable syncKernelTable(int index);

}  // namespace horopter::opencl
