// The telemetry log; see horopter/hardware/telemetry.hpp.
#include "horopter/hardware/telemetry.hpp"

#include <cerrno>

#include "file_output.hpp"
#include "horopter/core/error.hpp"
#include "json_text.hpp"

namespace horopter::hw {

namespace {

using detail::Json;
using detail::jsonNumber;

Json angles(const HeadAngles& a) {
  return Json{{"pan", jsonNumber(a.pan)},
              {"tilt", jsonNumber(a.tilt)},
              {"vergence", jsonNumber(a.vergence)}};
}

Json velocity(const BaseVelocity& v) {
  return Json{{"linear", jsonNumber(v.linear)}, {"angular", jsonNumber(v.angular)}};
}

}  // namespace

TelemetryLog::TelemetryLog(const std::string& path) : path_(path) {
  errno = 0;
  out_.open(path);
  if (!out_) detail::throwWriteError("telemetry log", path, errno);
}

std::string TelemetryLog::toJson(const TelemetrySample& s) {
  Json j;
  j["t"] = jsonNumber(s.t);
  j["head_commanded"] = s.headCommanded ? angles(*s.headCommanded) : Json(nullptr);
  j["head_measured"] = s.headMeasured ? angles(s.headMeasured->angles) : Json(nullptr);
  j["base_commanded"] = s.baseCommanded ? velocity(*s.baseCommanded) : Json(nullptr);
  j["base_sent"] = velocity(s.baseSent);
  j["odometry"] = s.odometry ? Json{{"x", jsonNumber(s.odometry->x)},
                                    {"y", jsonNumber(s.odometry->y)},
                                    {"heading", jsonNumber(s.odometry->heading)},
                                    {"velocity", velocity(s.odometry->velocity)}}
                             : Json(nullptr);
  j["estop"] = s.emergencyStop;
  j["faults"] = Json{{"head_link", s.head.linkUp},
                     {"head_timeouts", s.head.timeouts},
                     {"head_corrupt", s.head.corruptReplies},
                     {"head_last", s.head.lastFault},
                     {"base_link", s.base.linkUp},
                     {"base_status_fresh", s.base.statusFresh},
                     {"base_watchdog_trips", s.base.watchdogTrips},
                     {"base_status_timeouts", s.base.statusTimeouts},
                     {"base_last", s.base.lastFault}};
  return detail::jsonText(j);
}

void TelemetryLog::write(const TelemetrySample& sample) {
  const std::string line = toJson(sample);  // one object per line: JSON Lines
  std::lock_guard lock(mutex_);
  out_ << line << '\n';
  detail::checkStream(out_, path_, "telemetry log");  // flushed per line; a full disk throws
  ++lines_;
}

}  // namespace horopter::hw
