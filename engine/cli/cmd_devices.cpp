// `horopter devices`: the CPU, the backends and the OpenCL devices here.
#include <iostream>

#include "command_options.hpp"
#include "commands.hpp"
#include "horopter/kernels/backend.hpp"
#include "horopter/kernels/devices.hpp"
#include "json_text.hpp"
#include "report_format.hpp"

namespace horopter::cli {

namespace {

constexpr CommandOption kOptions[] = {
    {.kind = OptionKind::Switch, .flag = "--json", .help = "one JSON object on stdout"},
};

}  // namespace

int runDevices(Args& args) {
  if (args.flag("--help") || args.flag("-h")) {
    std::cout << "Usage: horopter devices [--json]\n\n"
                 "Lists the CPU and its SIMD features, every backend this build knows (and\n"
                 "whether it runs here), and the OpenCL platforms and devices. `auto` picks the\n"
                 "last available backend; HOROPTER_BACKEND=name overrides it. OpenCL is chosen\n"
                 "with --backend opencl (a GPU if present, else the CPU device), opencl:N or a\n"
                 "part of a device's name.\n\n"
              << commandOptionsHelp(kOptions);
    return 0;
  }
  const CommandOptions opts(args, kOptions);
  args.finish("devices");
  const bool asJson = opts.on("--json");
  const CpuInfo cpu = probeCpu();
  const OpenClReport cl = probeOpenCl();
  const Backend& chosen = findBackend("auto");

  if (asJson) {
    using detail::Json;
    Json backends = Json::array();
    for (const Backend* b : registeredBackends())
      backends.push_back(Json{{"name", b->name},
                              {"available", b->available},
                              {"description", b->description},
                              {"reason", b->unavailableReason}});
    Json devices = Json::array();
    for (std::size_t i = 0; i < cl.devices.size(); ++i) {
      const auto& d = cl.devices[i];
      devices.push_back(Json{{"backend", "opencl:" + std::to_string(i)},
                             {"platform", d.platform},
                             {"device", d.device},
                             {"platform_name", d.platformName},
                             {"name", d.deviceName},
                             {"type", d.type},
                             {"version", d.version},
                             {"compute_units", d.computeUnits},
                             {"global_mem_bytes", d.globalMemBytes}});
    }
    const Json o{
        {"cpu",
         {{"model", cpu.model}, {"threads", cpu.hardwareThreads}, {"features", cpu.features}}},
        {"backends", std::move(backends)},
        {"auto", chosen.name},
        {"opencl", {{"built", cl.built}, {"error", cl.error}, {"devices", std::move(devices)}}}};
    writeJsonLine(detail::jsonText(o));
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
