// Building the front end's program for a device: from the embedded sources,
// or from a program binary cached on disk under $XDG_CACHE_HOME/horopter
// (~/.cache/horopter without it), keyed by the device's name, its driver
// version, the build options and a hash of the sources. An entry that does
// not match its key, fails its checksum or does not build is rebuilt from
// source and rewritten, never trusted.
#pragma once

#include <cstdint>
#include <string>

#include "opencl/cl_api.hpp"
#include "opencl/device.hpp"

namespace horopter::opencl {

struct BuiltProgram {
  cl_program program = nullptr;  // owned by the caller
  ProgramOrigin origin = ProgramOrigin::Source;
  std::string cacheFile;  // the entry used or written ("" without a cache directory)
};

// The build options every program uses.
std::string buildOptions();

// 64-bit FNV-1a of all embedded sources (with the build options).
std::uint64_t sourceHash();

// The cache directory, or "" when neither XDG_CACHE_HOME nor HOME is set.
// HOROPTER_OPENCL_CACHE=0 turns the disk cache off.
std::string cacheDirectory();

// Builds (or loads) the program for `device`; throws horopter::Error with
// the build log when the sources do not build. Not cached in process: see
// Device::program().
// `extraOptions` (" -DNAME=value ..."): added to buildOptions() and to the
// cache entry's key (the tiled matcher's variants, tiled_variant.hpp).
BuiltProgram buildProgram(const DeviceDesc& device, cl_context context,
                          const std::string& extraOptions = "");

// Test hook: when set (or with HOROPTER_OPENCL_FAIL_BUILD=1 in the
// environment), builds fail as a compiler error would, to exercise the
// fallback. Programs already built in this process stay usable.
void setInjectedBuildFailure(bool on);
bool injectedBuildFailure();

}  // namespace horopter::opencl
