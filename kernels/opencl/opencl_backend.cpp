#include "opencl/opencl_backend.hpp"

#include <algorithm>
#include <cctype>

#include "common/kernel_table.hpp"
#include "horopter/core/error.hpp"
#include "opencl/device.hpp"
#include "opencl/sync_kernels.hpp"

namespace horopter::opencl {

namespace {

int defaultDevice() {
  const auto& list = devices();
  for (const Device* d : list)
    if (d->desc().gpu) return d->desc().index;
  return list.empty() ? -1 : 0;
}

std::string nameOf(int index) {
  return index == defaultDevice() ? "opencl" : "opencl:" + std::to_string(index);
}

std::string lower(std::string s) {
  for (char& c : s)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string deviceList() {
  std::string out;
  for (const Device* d : devices())
    out += (out.empty() ? "" : ", ") + ("opencl:" + std::to_string(d->desc().index)) + " (" +
           d->desc().name + ")";
  return out.empty() ? "none" : out;
}

}  // namespace

std::vector<Backend> makeBackends() {
  std::vector<Backend> out;
  const auto& list = devices();
  const int chosen = defaultDevice();
  if (chosen < 0) {
    Backend b;
    b.name = "opencl";
    b.description = "OpenCL kernels on the default device (a GPU if present, else the CPU)";
    b.unavailableReason = probeError();
    out.push_back(b);
    return out;
  }
  std::vector<int> order = {chosen};
  for (const Device* d : list)
    if (d->desc().index != chosen && d->desc().index < kMaxBackendDevices)
      order.push_back(d->desc().index);
  for (int index : order) {
    const DeviceDesc& d = list[static_cast<std::size_t>(index)]->desc();
    Backend b;
    b.name = nameOf(index);
    b.description = "OpenCL kernels on " + d.name + " (opencl:" + std::to_string(index) + ", " +
                    d.platformName + "); speckle filter on the CPU";
    b.available = index < kMaxBackendDevices;
    if (!b.available) b.unavailableReason = "only the first 8 OpenCL devices get a backend";
    if (b.available) b.kernels = std::make_shared<const KernelTable>(syncKernelTable(index));
    out.push_back(b);
  }
  return out;
}

std::string resolveBackendName(const std::string& wanted) {
  const auto& list = devices();
  if (wanted.rfind("opencl:", 0) == 0) {
    const std::string digits = wanted.substr(7);
    const bool number = !digits.empty() && digits.size() < 6 &&
                        std::all_of(digits.begin(), digits.end(), [](char c) {
                          return std::isdigit(static_cast<unsigned char>(c));
                        });
    const int index = number ? std::stoi(digits) : -1;
    if (index < 0 || index >= static_cast<int>(list.size()))
      throw Error("no OpenCL device '" + wanted + "': this machine has " + deviceList() +
                  (list.empty() ? " (" + probeError() + ")" : "") +
                  "; `horopter devices` lists them");
    if (index >= kMaxBackendDevices)
      throw Error("OpenCL device " + wanted + " has no backend: only the first " +
                  std::to_string(kMaxBackendDevices) + " devices get one");
    return nameOf(index);
  }
  if (wanted.size() < 2) return "";
  const std::string needle = lower(wanted);
  for (const Device* d : list) {
    if (lower(d->desc().name).find(needle) != std::string::npos &&
        d->desc().index < kMaxBackendDevices)
      return nameOf(d->desc().index);
  }
  return "";
}

int deviceIndexOf(const std::string& backendName) {
  if (backendName == "opencl") return defaultDevice();
  for (const Device* d : devices())
    if (backendName == "opencl:" + std::to_string(d->desc().index)) return d->desc().index;
  return -1;
}

}  // namespace horopter::opencl
