#include "opencl/program_cache.hpp"

#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <vector>

#include "horopter/core/error.hpp"
#include "opencl/cl_sources.hpp"

namespace horopter::opencl {

namespace {

std::atomic<bool> g_injected{false};

// Makes a build fail in the compiler itself, as a broken driver would.
const char* const kInjectedFailure =
    "#ifdef HOROPTER_INJECT_BUILD_FAILURE\n"
    "#error injected build failure (HOROPTER_OPENCL_FAIL_BUILD or the test hook)\n"
    "#endif\n";

constexpr char kMagic[] = "HOROPTER-CL-PROGRAM-CACHE 1\n";

std::uint64_t fnv1a(const void* data, std::size_t size, std::uint64_t h = 1469598103934665603ull) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i) {
    h ^= p[i];
    h *= 1099511628211ull;
  }
  return h;
}

std::vector<const char*> allSources() {
  return {kInjectedFailure, sources::prefilter, sources::sad,    sources::sadTiled,
          sources::sadBand, sources::lrCheck,   sources::median, sources::horopterMask};
}

std::string hex(std::uint64_t v) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

// What an entry must match: anything that changes the binary.
std::string cacheKey(const DeviceDesc& device, const std::string& extraOptions) {
  return "device=" + device.name + "\nplatform=" + device.platformName +
         "\ndriver=" + device.driverVersion + "\nversion=" + device.version +
         "\noptions=" + buildOptions() + extraOptions + "\nsources=" + hex(sourceHash()) + "\n";
}

std::string buildLog(cl_program program, cl_device_id device) {
  size_t size = 0;
  clGetProgramBuildInfo(program, device, CL_PROGRAM_BUILD_LOG, 0, nullptr, &size);
  std::string log(size, '\0');
  if (size > 0)
    clGetProgramBuildInfo(program, device, CL_PROGRAM_BUILD_LOG, size, log.data(), nullptr);
  while (!log.empty() && (log.back() == '\0' || log.back() == '\n'))
    log.pop_back();
  return log;
}

cl_program buildFromSource(const DeviceDesc& device, cl_context context,
                           const std::string& extraOptions) {
  std::vector<const char*> srcs = allSources();
  cl_int err = CL_SUCCESS;
  cl_program program = clCreateProgramWithSource(context, static_cast<cl_uint>(srcs.size()),
                                                 srcs.data(), nullptr, &err);
  check(err, "creating the program from source");
  std::string options = buildOptions() + extraOptions;
  if (injectedBuildFailure()) options += " -DHOROPTER_INJECT_BUILD_FAILURE";
  err = clBuildProgram(program, 1, &device.id, options.c_str(), nullptr, nullptr);
  if (err != CL_SUCCESS) {
    const std::string log = buildLog(program, device.id);
    clReleaseProgram(program);
    throw Error("OpenCL: building the front-end kernels for " + device.name + " failed (" +
                errorName(err) + "):\n" + log);
  }
  return program;
}

// The binary of a program built for one device.
std::vector<unsigned char> programBinary(cl_program program) {
  size_t size = 0;
  check(clGetProgramInfo(program, CL_PROGRAM_BINARY_SIZES, sizeof(size), &size, nullptr),
        "reading the program binary size");
  std::vector<unsigned char> binary(size);
  unsigned char* ptr = binary.data();
  check(clGetProgramInfo(program, CL_PROGRAM_BINARIES, sizeof(ptr), &ptr, nullptr),
        "reading the program binary");
  return binary;
}

// Entry layout: magic, key length, key, binary size, FNV-1a of the binary,
// the binary. Returns false (and says why) unless all of it checks out.
bool readEntry(const std::string& path, const std::string& key, std::vector<unsigned char>& out,
               std::string& why) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    why = "no entry";
    return false;
  }
  std::string magic(sizeof kMagic - 1, '\0');
  in.read(magic.data(), static_cast<std::streamsize>(magic.size()));
  if (!in || magic != kMagic) {
    why = "not a Horopter program cache entry";
    return false;
  }
  std::uint64_t keySize = 0, binSize = 0, binHash = 0;
  in.read(reinterpret_cast<char*>(&keySize), sizeof keySize);
  if (!in || keySize != key.size()) {
    why = "stale (built for another device, driver or source)";
    return false;
  }
  std::string storedKey(keySize, '\0');
  in.read(storedKey.data(), static_cast<std::streamsize>(keySize));
  if (!in || storedKey != key) {
    why = "stale (built for another device, driver or source)";
    return false;
  }
  in.read(reinterpret_cast<char*>(&binSize), sizeof binSize);
  in.read(reinterpret_cast<char*>(&binHash), sizeof binHash);
  if (!in || binSize == 0 || binSize > (std::uint64_t{1} << 31)) {
    why = "corrupt (bad binary size)";
    return false;
  }
  out.resize(binSize);
  in.read(reinterpret_cast<char*>(out.data()), static_cast<std::streamsize>(binSize));
  if (!in || in.peek() != std::char_traits<char>::eof() ||
      fnv1a(out.data(), out.size()) != binHash) {
    why = "corrupt (checksum mismatch or truncated)";
    return false;
  }
  return true;
}

// Written to a temporary file and renamed, so a reader never sees half an entry.
void writeEntry(const std::string& path, const std::string& key,
                const std::vector<unsigned char>& binary) {
  const std::string tmp = path + ".tmp" + std::to_string(::getpid());
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) return;
    const std::uint64_t keySize = key.size(), binSize = binary.size();
    const std::uint64_t binHash = fnv1a(binary.data(), binary.size());
    out.write(kMagic, sizeof kMagic - 1);
    out.write(reinterpret_cast<const char*>(&keySize), sizeof keySize);
    out.write(key.data(), static_cast<std::streamsize>(key.size()));
    out.write(reinterpret_cast<const char*>(&binSize), sizeof binSize);
    out.write(reinterpret_cast<const char*>(&binHash), sizeof binHash);
    out.write(reinterpret_cast<const char*>(binary.data()),
              static_cast<std::streamsize>(binary.size()));
    if (!out) {
      std::error_code ec;
      std::filesystem::remove(tmp, ec);
      return;
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) std::filesystem::remove(tmp, ec);
}

cl_program buildFromBinary(const DeviceDesc& device, cl_context context,
                           const std::string& extraOptions,
                           const std::vector<unsigned char>& binary) {
  const unsigned char* ptr = binary.data();
  const size_t size = binary.size();
  cl_int status = CL_SUCCESS, err = CL_SUCCESS;
  cl_program program =
      clCreateProgramWithBinary(context, 1, &device.id, &size, &ptr, &status, &err);
  if (err != CL_SUCCESS || status != CL_SUCCESS) {
    if (program) clReleaseProgram(program);
    return nullptr;
  }
  const std::string options = buildOptions() + extraOptions;
  if (clBuildProgram(program, 1, &device.id, options.c_str(), nullptr, nullptr) != CL_SUCCESS) {
    clReleaseProgram(program);
    return nullptr;
  }
  return program;
}

}  // namespace

std::string buildOptions() {
  return "-cl-std=CL1.2";
}

std::uint64_t sourceHash() {
  std::uint64_t h = fnv1a(buildOptions().data(), buildOptions().size());
  for (const char* s : allSources())
    h = fnv1a(s, std::char_traits<char>::length(s) + 1, h);
  return h;
}

std::string cacheDirectory() {
  const char* off = std::getenv("HOROPTER_OPENCL_CACHE");
  if (off != nullptr && std::string(off) == "0") return "";
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  if (xdg != nullptr && *xdg == '/') return std::string(xdg) + "/horopter";
  const char* home = std::getenv("HOME");
  if (home != nullptr && *home == '/') return std::string(home) + "/.cache/horopter";
  return "";
}

BuiltProgram buildProgram(const DeviceDesc& device, cl_context context,
                          const std::string& extraOptions) {
  BuiltProgram built;
  const std::string dir = injectedBuildFailure() ? "" : cacheDirectory();
  if (dir.empty()) {
    built.program = buildFromSource(device, context, extraOptions);
    return built;
  }
  const std::string key = cacheKey(device, extraOptions);
  built.cacheFile = dir + "/opencl-" + hex(fnv1a(key.data(), key.size())) + ".bin";
  std::vector<unsigned char> binary;
  std::string why;
  if (readEntry(built.cacheFile, key, binary, why)) {
    built.program = buildFromBinary(device, context, extraOptions, binary);
    if (built.program) {
      built.origin = ProgramOrigin::DiskCache;
      return built;
    }
    why = "rejected by the driver";
  }
  if (why != "no entry") {
    std::cerr << "horopter: OpenCL program cache entry " << built.cacheFile << " is " << why
              << "; rebuilding it from source\n";
    built.origin = ProgramOrigin::RebuiltAfterBadCacheEntry;
  }
  built.program = buildFromSource(device, context, extraOptions);
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (!ec) writeEntry(built.cacheFile, key, programBinary(built.program));
  return built;
}

void setInjectedBuildFailure(bool on) {
  g_injected = on;
}

bool injectedBuildFailure() {
  if (g_injected) return true;
  const char* env = std::getenv("HOROPTER_OPENCL_FAIL_BUILD");
  return env != nullptr && std::string(env) == "1";
}

}  // namespace horopter::opencl
