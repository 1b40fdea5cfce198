// The telemetry log; see horopter/hardware/telemetry.hpp.
#include "horopter/hardware/telemetry.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "horopter/core/error.hpp"

namespace horopter::hw {

namespace {

std::string num(double v) {
  if (!std::isfinite(v)) return "null";
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

std::string quoted(const std::string& s) {
  std::string o = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') o += '\\';
    if (static_cast<unsigned char>(c) >= 0x20) o += c;
  }
  return o + "\"";
}

std::string angles(const HeadAngles& a) {
  return "{\"pan\": " + num(a.pan) + ", \"tilt\": " + num(a.tilt) +
         ", \"vergence\": " + num(a.vergence) + "}";
}

std::string velocity(const BaseVelocity& v) {
  return "{\"linear\": " + num(v.linear) + ", \"angular\": " + num(v.angular) + "}";
}

}  // namespace

TelemetryLog::TelemetryLog(const std::string& path) : out_(path) {
  if (!out_) throw Error("cannot write the telemetry log " + path + ": check the folder exists");
}

std::string TelemetryLog::toJson(const TelemetrySample& s) {
  std::ostringstream o;
  o << "{\"t\": " << num(s.t);
  o << ", \"head_commanded\": " << (s.headCommanded ? angles(*s.headCommanded) : "null");
  if (s.headMeasured) {
    o << ", \"head_measured\": " << angles(s.headMeasured->angles);
  } else {
    o << ", \"head_measured\": null";
  }
  o << ", \"base_commanded\": " << (s.baseCommanded ? velocity(*s.baseCommanded) : "null");
  o << ", \"base_sent\": " << velocity(s.baseSent);
  if (s.odometry) {
    o << ", \"odometry\": {\"x\": " << num(s.odometry->x) << ", \"y\": " << num(s.odometry->y)
      << ", \"heading\": " << num(s.odometry->heading)
      << ", \"velocity\": " << velocity(s.odometry->velocity) << "}";
  } else {
    o << ", \"odometry\": null";
  }
  o << ", \"estop\": " << (s.emergencyStop ? "true" : "false");
  o << ", \"faults\": {\"head_link\": " << (s.head.linkUp ? "true" : "false")
    << ", \"head_timeouts\": " << s.head.timeouts << ", \"head_corrupt\": " << s.head.corruptReplies
    << ", \"head_last\": " << quoted(s.head.lastFault)
    << ", \"base_link\": " << (s.base.linkUp ? "true" : "false")
    << ", \"base_status_fresh\": " << (s.base.statusFresh ? "true" : "false")
    << ", \"base_watchdog_trips\": " << s.base.watchdogTrips
    << ", \"base_status_timeouts\": " << s.base.statusTimeouts
    << ", \"base_last\": " << quoted(s.base.lastFault) << "}}";
  return o.str();
}

void TelemetryLog::write(const TelemetrySample& sample) {
  const std::string line = toJson(sample);
  std::lock_guard lock(mutex_);
  out_ << line << '\n';
  out_.flush();
  ++lines_;
}

}  // namespace horopter::hw
