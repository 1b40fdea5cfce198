// What this machine offers: CPU features, registered backends, OpenCL devices.
#pragma once

#include "horopter/core/export.hpp"

#include <string>
#include <vector>

namespace horopter {

struct HOROPTER_API CpuInfo {
  std::string model;             // from /proc/cpuinfo, or "unknown"
  unsigned hardwareThreads = 0;  // std::thread::hardware_concurrency
  std::vector<std::string>
      features;  // the SIMD features Horopter can use: sse4.2, avx2, avx512bw...
};

struct HOROPTER_API OpenClDevice {
  int platform = 0;
  int device = 0;
  std::string platformName;
  std::string deviceName;
  std::string type;     // "cpu", "gpu", "accelerator", "other"
  std::string version;  // OpenCL version string of the device
  unsigned computeUnits = 0;
  unsigned long long globalMemBytes = 0;
};

struct HOROPTER_API OpenClReport {
  bool built = false;  // compiled with HOROPTER_WITH_OPENCL
  std::string error;   // why no device could be listed, when any
  std::vector<OpenClDevice> devices;
};

HOROPTER_API CpuInfo probeCpu();
HOROPTER_API OpenClReport probeOpenCl();

}  // namespace horopter
