// `horopter base`: drive a Segway RMP (SocketCAN, its USB interface, or the
// simulator) at a velocity for a while and print the odometry.
#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <memory>
#include <thread>

#include "command_options.hpp"
#include "commands.hpp"
#include "horopter/core/error.hpp"
#include "horopter/hardware/can_transports.hpp"
#include "horopter/hardware/rmp_base.hpp"
#include "horopter/hardware/serial_port.hpp"
#include "horopter/hardware/sim_rmp.hpp"
#include "json_text.hpp"

namespace horopter::cli {

namespace {

std::atomic<bool> gBaseInterrupted{false};
extern "C" void onBaseInterrupt(int) {
  gBaseInterrupted.store(true);
}

const char* kBaseHelp =
    "Usage: horopter base (--can IF | --usb DEV | --sim) [options]\n\n"
    "Drives the Segway RMP at a velocity for a duration, sending the command at 20 Hz as the\n"
    "pipeline would (the driver's own 200 ms watchdog stops the base if commands stop), then\n"
    "stops it and prints the odometry from the RMP's status frames.\n\n"
    "Stopping, at the end of --duration or on Ctrl-C (exit code 130), is a ramp, not a jump:\n"
    "zero is commanded and the base slows at the 0.5 m/s^2 acceleration limit; after 1 s a\n"
    "last zero command ends any ramp still running. Measured on the simulator: from 0.4 m/s\n"
    "about 0.8 s and 0.17 m, from 0.5 m/s about 1 s and 0.26 m. To stop without the ramp,\n"
    "press the RMP's own e-stop button.\n\n"
    "Options:\n";

constexpr CommandOption kOptions[] = {
    {.kind = OptionKind::Text,
     .flag = "--can",
     .value = "IF",
     .help = "SocketCAN interface, e.g. can0"},
    {.kind = OptionKind::Text,
     .flag = "--usb",
     .value = "DEV",
     .help = "the RMP's USB interface as a serial device, e.g. /dev/ttyUSB1"},
    {.kind = OptionKind::Integer,
     .flag = "--baud",
     .value = "N",
     .min = 300,
     .max = 10000000,
     .fallback = "460800",
     .help = "--usb baud rate (460800: as libsegwayrmp)"},
    {.kind = OptionKind::Switch,
     .flag = "--sim",
     .help = "a simulated RMP on a pseudo-terminal (through --usb's serial path)"},
    {.kind = OptionKind::Choice,
     .flag = "--model",
     .value = "M",
     .fallback = "rmp200",
     .choices = "rmp200,rmp400,rmp100,rmp50",
     .help = "the counts scaling"},
    {.kind = OptionKind::Number,
     .flag = "--linear",
     .value = "V",
     .min = -10,
     .max = 10,
     .unit = "m/s",
     .fallback = "0",
     .help = "forward velocity"},
    {.kind = OptionKind::Number,
     .flag = "--angular",
     .value = "W",
     .min = -10,
     .max = 10,
     .unit = "rad/s",
     .fallback = "0",
     .help = "turn rate, positive turns left"},
    {.kind = OptionKind::Number,
     .flag = "--duration",
     .value = "S",
     .min = 0,
     .max = 60,
     .unit = "s",
     .fallback = "2",
     .help = "how long to drive, above 0"},
    {.kind = OptionKind::Number,
     .flag = "--max-linear",
     .value = "V",
     .min = 0,
     .max = 10,
     .unit = "m/s",
     .fallback = "0.5",
     .help = "safety limit, above 0"},
    {.kind = OptionKind::Number,
     .flag = "--max-angular",
     .value = "W",
     .min = 0,
     .max = 10,
     .unit = "rad/s",
     .fallback = "1.0",
     .help = "safety limit, above 0"},
    {.kind = OptionKind::Switch,
     .flag = "--estop",
     .help = "engage the latching emergency stop first: the base is held at zero (commands are "
             "ignored) and the state is printed"},
    {.kind = OptionKind::Switch, .flag = "--json", .help = "one JSON object per printed reading"},
};

void print(const std::optional<hw::Odometry>& o, const hw::BaseHealth& h, double t, bool estop,
           bool json) {
  if (json) {
    using detail::Json;
    using detail::jsonNumber;
    const Json line = o ? Json{{"t", jsonNumber(t, 2)},
                               {"x", jsonNumber(o->x, 4)},
                               {"y", jsonNumber(o->y, 4)},
                               {"heading", jsonNumber(o->heading, 4)},
                               {"linear", jsonNumber(o->velocity.linear, 3)},
                               {"angular", jsonNumber(o->velocity.angular, 3)},
                               {"sent_linear", jsonNumber(h.lastSent.linear, 3)},
                               {"sent_angular", jsonNumber(h.lastSent.angular, 3)},
                               {"estop", estop},
                               {"status_fresh", h.statusFresh}}
                        : Json{{"t", jsonNumber(t, 2)}, {"odometry", nullptr}, {"estop", estop}};
    std::cout << detail::jsonText(line) << std::endl;
    return;
  }
  char line[320];
  if (!o) {
    std::snprintf(line, sizeof line, "t=%5.2fs  no status from the base yet  estop=%s", t,
                  estop ? "true" : "false");
  } else {
    std::snprintf(line, sizeof line,
                  "t=%5.2fs  x=%+.3f m  y=%+.3f m  heading=%+.3f rad  v=%+.3f m/s  w=%+.3f rad/s  "
                  "sent v=%+.3f w=%+.3f%s",
                  t, o->x, o->y, o->heading, o->velocity.linear, o->velocity.angular,
                  h.lastSent.linear, h.lastSent.angular, estop ? "  E-STOP" : "");
  }
  std::cout << line << std::endl;
}

}  // namespace

int runBase(Args& args) {
  if (args.flag("--help") || args.flag("-h")) {
    std::cout << kBaseHelp << commandOptionsHelp(kOptions);
    return 0;
  }
  const CommandOptions opts(args, kOptions);
  args.finish("base");
  const auto can = opts.optionalText("--can");
  const auto usb = opts.optionalText("--usb");
  const bool sim = opts.on("--sim");
  const int baud = static_cast<int>(opts.integer("--baud"));
  const double linear = opts.number("--linear");
  const double angular = opts.number("--angular");
  const double duration = opts.number("--duration");
  hw::RmpBaseOptions options;
  options.scaling = asUsageError([&] { return hw::rmp::scalingByName(opts.text("--model")); });
  options.limits.maxLinear = opts.number("--max-linear");
  options.limits.maxAngular = opts.number("--max-angular");
  const bool estop = opts.on("--estop");
  const bool json = opts.on("--json");
  if (int(can.has_value()) + int(usb.has_value()) + int(sim) != 1)
    throw UsageError("give exactly one of --can IF, --usb DEV or --sim");
  if (!(duration > 0)) throw UsageError("--duration must be in (0, 60] s");
  asUsageError([&] { hw::validate(options.limits); });
  if (std::abs(linear) > options.limits.maxLinear || std::abs(angular) > options.limits.maxAngular)
    std::cerr << "base: the command exceeds the safety limits and will be clamped to "
              << options.limits.maxLinear << " m/s, " << options.limits.maxAngular << " rad/s\n";

  // --sim: the simulated RMP on a pseudo-terminal, driven through the same
  // serial port and USB framing as --usb.
  std::unique_ptr<hw::SimRmpOnPty> simRmp;
  std::unique_ptr<hw::CanTransport> transport;
  if (sim) {
    hw::SimRmpOptions so;
    so.scaling = options.scaling;
    simRmp = std::make_unique<hw::SimRmpOnPty>(so);
    transport = std::make_unique<hw::RmpUsbCan>(
        std::make_unique<hw::SerialPort>(simRmp->port(), hw::SerialOptions{baud}));
  } else if (can) {
    transport = std::make_unique<hw::SocketCan>(*can);
  } else {
    transport = std::make_unique<hw::RmpUsbCan>(
        std::make_unique<hw::SerialPort>(*usb, hw::SerialOptions{baud}));
  }
  hw::RmpBase base(std::move(transport), options);
  std::cerr << "base: " << base.name() << (sim ? " (simulated)" : "") << "\n";
  if (estop) base.emergencyStop();
  std::signal(SIGINT, onBaseInterrupt);

  const auto start = hw::Clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(hw::Clock::now() - start).count(); };
  double lastPrint = -1;
  while (elapsed() < duration && !gBaseInterrupted) {
    base.command({linear, angular});
    if (elapsed() - lastPrint >= 0.2) {
      lastPrint = elapsed();
      print(base.odometry(), base.health(), lastPrint, base.emergencyStopped(), json);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  // Stop: zero commands until the base reports standing still (at most 1 s), then shut down.
  const auto stopBy = hw::Clock::now() + std::chrono::seconds(1);
  while (hw::Clock::now() < stopBy) {
    base.command({0, 0});
    const auto o = base.odometry();
    if (o && std::abs(o->velocity.linear) < 1e-3 && std::abs(o->velocity.angular) < 1e-3) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  base.shutdown();
  const hw::BaseHealth h = base.health();
  print(base.odometry(), h, elapsed(), base.emergencyStopped(), json);
  std::cerr << "base: stopped; " << h.framesSent << " command frames, " << h.seriesReceived
            << " status series, " << h.watchdogTrips << " watchdog trips, " << h.statusTimeouts
            << " status timeouts, " << h.badFrames << " bad frames"
            << (h.lastFault.empty() ? "" : "; last fault: " + h.lastFault) << "\n";
  if (gBaseInterrupted) return 130;
  if (!h.linkUp) throw Error("lost the link to the base: " + h.lastFault);
  if (h.seriesReceived == 0)
    throw Error("the base never reported its status (check the bus and the power)");
  return 0;
}

}  // namespace horopter::cli
