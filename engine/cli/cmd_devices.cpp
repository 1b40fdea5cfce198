// `horopter devices`: the CPU, the backends and the OpenCL devices here.
#include <cstdio>
#include <iostream>
#include <sstream>

#include "commands.hpp"
#include "horopter/kernels/backend.hpp"
#include "horopter/kernels/devices.hpp"

namespace horopter::cli {

namespace {

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (static_cast<unsigned char>(c) >= 0x20) out += c;
  }
  return out + "\"";
}

}  // namespace

int runDevices(Args& args) {
  if (args.flag("--help") || args.flag("-h")) {
    std::cout << "Usage: horopter devices [--json]\n\n"
                 "Lists the CPU and its SIMD features, every backend this build knows (and\n"
                 "whether it runs here), and the OpenCL platforms and devices. `auto` picks the\n"
                 "last available backend; HOROPTER_BACKEND=name overrides it. OpenCL is chosen\n"
                 "with --backend opencl (a GPU if present, else the CPU device), opencl:N or a\n"
                 "part of a device's name.\n";
    return 0;
  }
  const bool asJson = args.flag("--json");
  args.finish("devices");
  const CpuInfo cpu = probeCpu();
  const OpenClReport cl = probeOpenCl();
  const Backend& chosen = findBackend("auto");

  if (asJson) {
    std::ostringstream o;
    o << "{\"cpu\": {\"model\": " << quoted(cpu.model) << ", \"threads\": " << cpu.hardwareThreads
      << ", \"features\": [";
    for (std::size_t i = 0; i < cpu.features.size(); ++i)
      o << (i ? ", " : "") << quoted(cpu.features[i]);
    o << "]}, \"backends\": [";
    bool first = true;
    for (const Backend* b : registeredBackends()) {
      o << (first ? "" : ", ") << "{\"name\": " << quoted(b->name)
        << ", \"available\": " << (b->available ? "true" : "false")
        << ", \"description\": " << quoted(b->description)
        << ", \"reason\": " << quoted(b->unavailableReason) << "}";
      first = false;
    }
    o << "], \"auto\": " << quoted(chosen.name)
      << ", \"opencl\": {\"built\": " << (cl.built ? "true" : "false")
      << ", \"error\": " << quoted(cl.error) << ", \"devices\": [";
    for (std::size_t i = 0; i < cl.devices.size(); ++i) {
      const auto& d = cl.devices[i];
      o << (i ? ", " : "") << "{\"backend\": \"opencl:" << i << "\", \"platform\": " << d.platform
        << ", \"device\": " << d.device << ", \"platform_name\": " << quoted(d.platformName)
        << ", \"name\": " << quoted(d.deviceName) << ", \"type\": " << quoted(d.type)
        << ", \"version\": " << quoted(d.version) << ", \"compute_units\": " << d.computeUnits
        << ", \"global_mem_bytes\": " << d.globalMemBytes << "}";
    }
    o << "]}}\n";
    std::cout << o.str();
    return 0;
  }
  std::cout << "CPU: " << cpu.model << " (" << cpu.hardwareThreads << " threads)\n  features:";
  for (const auto& f : cpu.features)
    std::cout << " " << f;
  std::cout << "\nBackends (auto = " << chosen.name << "):\n";
  for (const Backend* b : registeredBackends()) {
    std::cout << "  " << b->name << (b->available ? "  available  " : "  unavailable  ")
              << b->description;
    if (!b->available) std::cout << " (" << b->unavailableReason << ")";
    std::cout << "\n";
  }
  std::cout << "OpenCL devices (--backend opencl:N, or part of the name; --backend opencl = the "
               "first GPU, else the first device):\n";
  if (cl.devices.empty()) std::cout << "  none: " << cl.error << "\n";
  for (std::size_t i = 0; i < cl.devices.size(); ++i) {
    const auto& d = cl.devices[i];
    std::cout << "  opencl:" << i << "  " << d.type << "  " << d.deviceName << "\n    platform "
              << d.platform << " (" << d.platformName << "), device " << d.device << ", "
              << d.version << ", " << d.computeUnits << " compute units, "
              << (d.globalMemBytes >> 20) << " MiB global memory\n";
  }
  return 0;
}

}  // namespace horopter::cli
