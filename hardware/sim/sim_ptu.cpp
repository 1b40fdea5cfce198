// Simulated FLIR PTU on a pty: see include/horopter/hardware/sim_devices.hpp.
// Starts as a unit out of the box: echo on, verbose feedback.
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>

#include "horopter/hardware/sim_devices.hpp"

namespace horopter::hw {

SimPtu::SimPtu(SimPtuOptions options) : options_(options) {
  thread_ = std::thread([this] { run(); });
}

SimPtu::~SimPtu() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
}

void SimPtu::injectFault(DeviceFault fault, int count) {
  std::lock_guard lock(mutex_);
  fault_ = fault;
  faultCount_ = count;
}

void SimPtu::injectReply(std::string line, int count) {
  std::lock_guard lock(mutex_);
  injectedLine_ = std::move(line);
  injectedCount_ = count;
}

long SimPtu::position(bool pan) const {
  std::lock_guard lock(mutex_);
  return std::lround(pan ? pan_ : tilt_);
}

void SimPtu::advance(double seconds) {
  auto move = [seconds](double& at, long target, long speed) {
    const double step = speed * seconds;
    const double d = target - at;
    at = std::abs(d) <= step ? target : at + (d > 0 ? step : -step);
  };
  move(pan_, panTarget_, panSpeed_);
  move(tilt_, tiltTarget_, tiltSpeed_);
}

// The reply text (without the line end) to one command; called with mutex_ held.
std::string SimPtu::handle(const std::string& raw) {
  std::string cmd;
  for (char c : raw)
    cmd += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  std::size_t letters = 0;
  while (letters < cmd.size() && std::isalpha(static_cast<unsigned char>(cmd[letters])))
    ++letters;
  const std::string op = cmd.substr(0, letters);
  const std::string arg = cmd.substr(letters);
  long value = 0;
  const bool hasValue = !arg.empty();
  if (hasValue) {
    const auto [p, ec] = std::from_chars(arg.data(), arg.data() + arg.size(), value);
    if (ec != std::errc() || p != arg.data() + arg.size()) return "! Illegal argument";
  }
  auto query = [this](const std::string& what, long v) {
    return terse_ ? "* " + std::to_string(v) : "* Current " + what + " is " + std::to_string(v);
  };
  auto setPos = [&](bool pan) -> std::string {
    const long lo = pan ? options_.panMin : options_.tiltMin;
    const long hi = pan ? options_.panMax : options_.tiltMax;
    const std::string axis = pan ? "Pan" : "Tilt";
    if (value > hi) return "! Maximum allowable " + axis + " position is " + std::to_string(hi);
    if (value < lo) return "! Minimum allowable " + axis + " position is " + std::to_string(lo);
    (pan ? panTarget_ : tiltTarget_) = value;
    return "*";
  };
  auto setSpeed = [&](bool pan) -> std::string {
    if (value < 0 || value > options_.maxSpeed)
      return "! Maximum allowable " + std::string(pan ? "Pan" : "Tilt") + " speed is " +
             std::to_string(options_.maxSpeed);
    (pan ? panSpeed_ : tiltSpeed_) = value;
    return "*";
  };
  char resolution[32];
  std::snprintf(resolution, sizeof resolution, "%.4f", options_.resolutionArcSec);
  if (op == "FT") {
    terse_ = true;
    return "*";
  }
  if (op == "FV") {
    terse_ = false;
    return "*";
  }
  if (op == "ED") {
    echo_ = false;
    return "*";
  }
  if (op == "EE") {
    echo_ = true;
    return "*";
  }
  if (op == "CI") return "*";
  if (op == "H") {
    panTarget_ = std::lround(pan_);
    tiltTarget_ = std::lround(tilt_);
    return "*";
  }
  if (op == "PP") return hasValue ? setPos(true) : query("Pan position", std::lround(pan_));
  if (op == "TP") return hasValue ? setPos(false) : query("Tilt position", std::lround(tilt_));
  if (op == "PS") return hasValue ? setSpeed(true) : query("Pan speed", panSpeed_);
  if (op == "TS") return hasValue ? setSpeed(false) : query("Tilt speed", tiltSpeed_);
  if (op == "PR" || op == "TR")
    return terse_ ? std::string("* ") + resolution
                  : std::string("* ") + resolution + " seconds arc per position";
  if (op == "PN") return query("Minimum Pan position", options_.panMin);
  if (op == "PX") return query("Maximum Pan position", options_.panMax);
  if (op == "TN") return query("Minimum Tilt position", options_.tiltMin);
  if (op == "TX") return query("Maximum Tilt position", options_.tiltMax);
  return "! Illegal command";
}

void SimPtu::run() {
  std::string pending;
  auto last = std::chrono::steady_clock::now();
  bool awaiting = false;
  while (!stop_) {
    const auto in = pty_.read(256, std::chrono::milliseconds(5));
    const auto now = std::chrono::steady_clock::now();
    std::string out;
    {
      std::lock_guard lock(mutex_);
      advance(std::chrono::duration<double>(now - last).count());
      last = now;
      if (awaiting && std::lround(pan_) == panTarget_ && std::lround(tilt_) == tiltTarget_) {
        out += "*\r\n";
        awaiting = false;
      }
      for (std::uint8_t byte : in) {
        const char c = static_cast<char>(byte);
        if (c != ' ' && c != '\r' && c != '\n') {
          pending += c;
          continue;
        }
        if (pending.empty()) continue;
        ++commands_;
        if (echo_) out += pending + c;
        std::string upper;
        for (char p : pending)
          upper += static_cast<char>(std::toupper(static_cast<unsigned char>(p)));
        if (upper == "A") {
          awaiting = true;  // "*" once both axes are where they were sent
        } else {
          std::string reply = handle(pending);
          if (injectedCount_ > 0) {
            --injectedCount_;
            reply = injectedLine_;
          }
          if (faultCount_ > 0) {
            --faultCount_;
            switch (fault_) {
              case DeviceFault::kNone:
                break;
              case DeviceFault::kCorruptChecksum:
                reply[0] = '#';
                break;  // ASCII has no checksum: a mangled lead byte
              case DeviceFault::kShortFrame:
                reply = reply.substr(0, (reply.size() + 1) / 2);
                out += reply;
                reply.clear();
                break;
              case DeviceFault::kGarbage:
                reply = "\x13\x7f%$?";
                break;
              case DeviceFault::kNoReply:
                reply.clear();
                break;
              case DeviceFault::kDisconnect:
                pty_.closeMaster();
                reply.clear();
                break;
            }
          }
          if (!reply.empty()) out += reply + "\r\n";
        }
        pending.clear();
      }
    }
    if (!out.empty())
      pty_.write(std::span(reinterpret_cast<const std::uint8_t*>(out.data()), out.size()));
    if (!pty_.masterOpen()) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

}  // namespace horopter::hw
