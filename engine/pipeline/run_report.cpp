// The run summary as JSON, and the Chrome trace of a run.
#include <string>

#include "file_output.hpp"
#include "horopter/core/error.hpp"
#include "horopter/pipeline/scheduler.hpp"
#include "json_text.hpp"

namespace horopter {

using detail::Json;
using detail::jsonNumber;

std::string summaryJson(const RunSummary& s) {
  // Times to the microsecond; a value that is not finite (no frame timed)
  // is null, never a bare nan, which no JSON reader takes.
  const auto ms = [](double v) { return jsonNumber(v, 3); };
  Json j;
  j["frames"] = s.completed;
  j["captured"] = s.captured;
  j["dropped"] = s.dropped;
  j["seconds"] = ms(s.seconds);
  j["fps"] = ms(s.fps());
  j["latency_ms"] = ms(s.meanLatencyMs);
  j["max_latency_ms"] = ms(s.maxLatencyMs);
  j["stopped_by_request"] = s.stoppedByRequest;
  Json stages = Json::object();
  for (const StageSummary& st : s.stages)
    stages[st.name] = {{"frames", st.frames}, {"ms", ms(st.meanMs)}, {"fps", ms(st.fps())}};
  j["stages"] = std::move(stages);
  return detail::jsonText(j);
}

void writeChromeTrace(const RunSummary& s, const std::string& path) {
  // One event per line, so that the trace reads and diffs line by line.
  std::string text = "{\"displayTimeUnit\":\"ms\",\"traceEvents\":[\n";
  std::string separator;
  const auto add = [&](const Json& event) {
    text += separator + detail::jsonText(event);
    separator = ",\n";
  };
  // Lane names: 0 = capture, then the stages in order.
  for (std::size_t i = 0; i < s.stages.size(); ++i)
    add(Json{{"name", "thread_name"},
             {"ph", "M"},
             {"pid", 1},
             {"tid", i},
             {"args", {{"name", s.stages[i].name}}}});
  for (const TraceEvent& e : s.trace)
    add(Json{{"name", e.stage + " #" + std::to_string(e.frame)},
             {"cat", "frame"},
             {"ph", "X"},
             {"pid", 1},
             {"tid", e.lane},
             {"ts", jsonNumber(e.startUs, 3)},
             {"dur", jsonNumber(e.durationUs, 3)},
             {"args", {{"frame", e.frame}}}});
  text += separator.empty() ? "]}\n" : "\n]}\n";
  detail::writeFile(path, text, "trace");
}

}  // namespace horopter
