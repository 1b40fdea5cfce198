// The run summary as JSON, and the Chrome trace of a run.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "horopter/core/error.hpp"
#include "horopter/pipeline/scheduler.hpp"

namespace horopter {

namespace {

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", v);
  return buf;
}

}  // namespace

std::string summaryJson(const RunSummary& s) {
  // Times to the microsecond; a value that is not finite (no frame timed)
  // is null, never a bare nan, which no JSON reader takes.
  const auto ms = [](double v) -> nlohmann::ordered_json {
    if (!std::isfinite(v)) return nullptr;
    return std::round(v * 1000.0) / 1000.0;
  };
  nlohmann::ordered_json j;
  j["frames"] = s.completed;
  j["captured"] = s.captured;
  j["dropped"] = s.dropped;
  j["seconds"] = ms(s.seconds);
  j["fps"] = ms(s.fps());
  j["latency_ms"] = ms(s.meanLatencyMs);
  j["max_latency_ms"] = ms(s.maxLatencyMs);
  j["stopped_by_request"] = s.stoppedByRequest;
  nlohmann::ordered_json stages = nlohmann::ordered_json::object();
  for (const StageSummary& st : s.stages)
    stages[st.name] = {{"frames", st.frames}, {"ms", ms(st.meanMs)}, {"fps", ms(st.fps())}};
  j["stages"] = std::move(stages);
  return j.dump();
}

void writeChromeTrace(const RunSummary& s, const std::string& path) {
  std::ofstream out(path);
  if (!out) throw Error("cannot write the trace to '" + path + "': check the directory exists");
  out << "{\"displayTimeUnit\": \"ms\", \"traceEvents\": [\n";
  // Lane names: 0 = capture, then the stages in order.
  for (std::size_t i = 0; i < s.stages.size(); ++i) {
    out << "{\"name\": \"thread_name\", \"ph\": \"M\", \"pid\": 1, \"tid\": " << i
        << ", \"args\": {\"name\": " << quoted(s.stages[i].name) << "}},\n";
  }
  for (std::size_t i = 0; i < s.trace.size(); ++i) {
    const TraceEvent& e = s.trace[i];
    out << "{\"name\": " << quoted(e.stage + " #" + std::to_string(e.frame))
        << ", \"cat\": \"frame\", \"ph\": \"X\", \"pid\": 1, \"tid\": " << e.lane
        << ", \"ts\": " << number(e.startUs) << ", \"dur\": " << number(e.durationUs)
        << ", \"args\": {\"frame\": " << e.frame << "}}" << (i + 1 < s.trace.size() ? ",\n" : "\n");
  }
  out << "]}\n";
  if (!out) throw Error("writing the trace to '" + path + "' failed (disk full?)");
}

}  // namespace horopter
