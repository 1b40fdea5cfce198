// `horopter head`: drive a pan-tilt(-vergence) head (DYNAMIXEL or FLIR PTU),
// or its simulator, and print the measured angles.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <functional>
#include <iostream>
#include <memory>
#include <sstream>
#include <thread>

#include "command_options.hpp"
#include "commands.hpp"
#include "horopter/core/error.hpp"
#include "horopter/hardware/dynamixel_head.hpp"
#include "horopter/hardware/ptu_head.hpp"
#include "horopter/hardware/serial_port.hpp"
#include "horopter/hardware/sim_devices.hpp"
#include "json_text.hpp"

namespace horopter::cli {

namespace {

std::atomic<bool> gHeadInterrupted{false};
extern "C" void onHeadInterrupt(int) {
  gHeadInterrupted.store(true);
}

const char* kHeadHelp =
    "Usage: horopter head (--port DEV | --sim) [--protocol dynamixel|ptu] [options]\n\n"
    "Moves the stereo head to the given angles (radians; pan positive turns right, tilt\n"
    "positive looks down, vergence = total angle between the optical axes) and prints the\n"
    "measured angles until they arrive. Without --pan/--tilt/--vergence: prints the\n"
    "measured angles once. Ctrl-C halts the head where it is.\n\n"
    "Options:\n";

constexpr CommandOption kOptions[] = {
    {.kind = OptionKind::Text,
     .flag = "--port",
     .value = "DEV",
     .help = "serial device, e.g. /dev/ttyUSB0"},
    {.kind = OptionKind::Switch,
     .flag = "--sim",
     .help = "a simulated device on a pseudo-terminal instead of --port"},
    {.kind = OptionKind::Choice,
     .flag = "--protocol",
     .value = "P",
     .fallback = "dynamixel",
     .choices = "dynamixel,ptu",
     .help = "DYNAMIXEL Protocol 2.0 (X series) or FLIR PTU (ASCII)"},
    {.kind = OptionKind::Integer,
     .flag = "--baud",
     .value = "N",
     .min = 300,
     .max = 10000000,
     .help = "baud rate (default 57600 for dynamixel, 9600 for ptu)"},
    {.kind = OptionKind::Text,
     .flag = "--ids",
     .value = "P,T[,L,R]",
     .help = "DYNAMIXEL IDs of pan, tilt and left/right vergence, all different (default 1,2; "
             "dynamixel only: a PTU has no IDs)"},
    {.kind = OptionKind::Number,
     .flag = "--pan",
     .value = "R",
     .min = -6.3,
     .max = 6.3,
     .unit = "rad",
     .help = "target pan angle"},
    {.kind = OptionKind::Number,
     .flag = "--tilt",
     .value = "R",
     .min = -6.3,
     .max = 6.3,
     .unit = "rad",
     .help = "target tilt angle"},
    {.kind = OptionKind::Number,
     .flag = "--vergence",
     .value = "R",
     .min = -6.3,
     .max = 6.3,
     .unit = "rad",
     .help = "target vergence (dynamixel with 4 IDs)"},
    {.kind = OptionKind::Number,
     .flag = "--speed",
     .value = "R",
     .min = 0,
     .max = 1,
     .unit = "rad/s",
     .fallback = "0.5",
     .help = "speed per axis, above 0"},
    {.kind = OptionKind::Number,
     .flag = "--tolerance",
     .value = "R",
     .min = 0,
     .max = 1,
     .unit = "rad",
     .fallback = "0.003",
     .help = "arrived when every axis is within R, above 0"},
    {.kind = OptionKind::Number,
     .flag = "--timeout",
     .value = "S",
     .min = 0,
     .max = 3600,
     .unit = "s",
     .fallback = "10",
     .help = "give up after S seconds (exit code 1), above 0"},
    {.kind = OptionKind::Switch, .flag = "--json", .help = "one JSON object per printed reading"},
};

std::vector<int> parseIds(const std::string& text) {
  std::vector<int> ids;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    try {
      std::size_t used = 0;
      const int id = std::stoi(item, &used);
      if (used != item.size() || id < 0 || id > 252) throw std::invalid_argument(item);
      ids.push_back(id);
    } catch (const std::exception&) {
      throw UsageError("--ids: '" + item + "' is not a DYNAMIXEL ID (0..252)");
    }
    if (std::count(ids.begin(), ids.end(), ids.back()) > 1)
      throw UsageError(
          "--ids: ID " + std::to_string(ids.back()) +
          " is given twice (pan, tilt and each vergence axis need a servo of their own)");
  }
  if (ids.size() != 2 && ids.size() != 4)
    throw UsageError("--ids takes 2 IDs (pan,tilt) or 4 (pan,tilt,left,right), got " +
                     std::to_string(ids.size()));
  return ids;
}

void print(const hw::HeadMeasurement& m, double t, bool json) {
  if (json) {
    using detail::jsonNumber;
    std::cout << detail::jsonText({{"t", jsonNumber(t, 2)},
                                   {"pan", jsonNumber(m.angles.pan, 4)},
                                   {"tilt", jsonNumber(m.angles.tilt, 4)},
                                   {"vergence", jsonNumber(m.angles.vergence, 4)}})
              << std::endl;
    return;
  }
  char line[200];
  std::snprintf(line, sizeof line, "t=%5.2fs  pan=%+.4f  tilt=%+.4f  vergence=%+.4f rad", t,
                m.angles.pan, m.angles.tilt, m.angles.vergence);
  std::cout << line << std::endl;
}

}  // namespace

int runHead(Args& args) {
  if (args.flag("--help") || args.flag("-h")) {
    std::cout << kHeadHelp << commandOptionsHelp(kOptions);
    return 0;
  }
  const CommandOptions opts(args, kOptions);
  args.finish("head");
  const bool sim = opts.on("--sim");
  const auto port = opts.optionalText("--port");
  const std::string protocol = opts.text("--protocol");
  const int baud =
      static_cast<int>(opts.optionalInteger("--baud").value_or(protocol == "ptu" ? 9600 : 57600));
  const auto idsText = opts.optionalText("--ids");
  if (idsText && protocol == "ptu")
    throw UsageError("--ids is for --protocol dynamixel: a FLIR PTU has no servo IDs");
  const std::vector<int> ids = parseIds(idsText.value_or("1,2"));
  const auto pan = opts.optionalNumber("--pan");
  const auto tilt = opts.optionalNumber("--tilt");
  const auto vergence = opts.optionalNumber("--vergence");
  const double speed = opts.number("--speed");
  const double tolerance = opts.number("--tolerance");
  const double timeout = opts.number("--timeout");
  const bool json = opts.on("--json");
  if (sim == port.has_value()) throw UsageError("give exactly one of --port DEV or --sim");
  if (!(speed > 0)) throw UsageError("--speed must be in (0, 1] rad/s");
  if (!(tolerance > 0) || !(timeout > 0)) throw UsageError("--tolerance and --timeout must be > 0");
  if (vergence && (protocol == "ptu" || ids.size() != 4))
    throw UsageError("--vergence needs a DYNAMIXEL head with 4 IDs (--ids pan,tilt,left,right)");

  std::unique_ptr<hw::SimDynamixelBus> simBus;
  std::unique_ptr<hw::SimPtu> simPtu;
  std::string device = port.value_or("");
  if (sim && protocol == "dynamixel") {
    std::vector<std::uint8_t> simIds;
    for (int id : ids)
      simIds.push_back(static_cast<std::uint8_t>(id));
    simBus = std::make_unique<hw::SimDynamixelBus>(simIds);
    device = simBus->port();
  } else if (sim) {
    simPtu = std::make_unique<hw::SimPtu>();
    device = simPtu->port();
  }
  auto serial = std::make_unique<hw::SerialPort>(device, hw::SerialOptions{baud});
  std::unique_ptr<hw::Head> head;
  std::function<hw::HeadHealth()> health;
  if (protocol == "dynamixel") {
    hw::DynamixelHeadOptions o;
    o.panId = static_cast<std::uint8_t>(ids[0]);
    o.tiltId = static_cast<std::uint8_t>(ids[1]);
    if (ids.size() == 4) {
      o.leftVergenceId = static_cast<std::uint8_t>(ids[2]);
      o.rightVergenceId = static_cast<std::uint8_t>(ids[3]);
      o.limits.vergenceMax = 0.5;
    }
    auto d = std::make_unique<hw::DynamixelHead>(std::move(serial), o);
    health = [p = d.get()] { return p->health(); };
    head = std::move(d);
  } else {
    auto d = std::make_unique<hw::PtuHead>(std::move(serial));
    health = [p = d.get()] { return p->health(); };
    head = std::move(d);
  }
  std::cerr << "head: " << head->name() << (sim ? " (simulated)" : "") << "\n";

  const auto start = hw::Clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(hw::Clock::now() - start).count(); };
  // Wait for the first reading.
  while (!head->measured() && elapsed() < timeout)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  auto m = head->measured();
  if (!m)
    throw Error("no angle reading from the head within " + std::to_string(timeout) +
                " s: " + health().lastFault);
  if (!pan && !tilt && !vergence) {
    print(*m, elapsed(), json);
    return 0;
  }
  hw::HeadAngles target = m->angles;
  if (pan) target.pan = *pan;
  if (tilt) target.tilt = *tilt;
  if (vergence) target.vergence = *vergence;
  const hw::HeadLimits l = head->limits();
  const hw::HeadAngles clamped{
      std::clamp(target.pan, l.panMin, l.panMax), std::clamp(target.tilt, l.tiltMin, l.tiltMax),
      l.hasVergence ? std::clamp(target.vergence, l.vergenceMin, l.vergenceMax) : 0};
  if (clamped.pan != target.pan || clamped.tilt != target.tilt ||
      clamped.vergence != target.vergence)
    std::cerr << "head: target clamped to the head's limits (pan " << l.panMin << ".." << l.panMax
              << ", tilt " << l.tiltMin << ".." << l.tiltMax << ")\n";
  head->command(clamped, speed);
  std::signal(SIGINT, onHeadInterrupt);
  double lastPrint = -1;
  while (true) {
    m = head->measured();
    const bool arrived = std::abs(m->angles.pan - clamped.pan) <= tolerance &&
                         std::abs(m->angles.tilt - clamped.tilt) <= tolerance &&
                         std::abs(m->angles.vergence - clamped.vergence) <= tolerance;
    const double t = elapsed();
    if (arrived || t - lastPrint >= 0.1) {
      print(*m, t, json);
      lastPrint = t;
    }
    if (arrived) break;
    if (gHeadInterrupted) {
      head->halt();
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      std::cerr << "head: interrupted, halted\n";
      return 130;
    }
    if (!health().linkUp) throw Error("lost the link to the head: " + health().lastFault);
    if (t > timeout) {
      head->halt();
      throw Error("the head did not reach the target within " + std::to_string(timeout) +
                  " s (last fault: " + (health().lastFault.empty() ? "none" : health().lastFault) +
                  ")");
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  const hw::HeadHealth h = health();
  std::cerr << "head: arrived; " << h.exchanges << " exchanges, " << h.timeouts << " timeouts, "
            << h.corruptReplies << " corrupt replies\n";
  return 0;
}

}  // namespace horopter::cli
