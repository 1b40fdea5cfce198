// openSource: a capture source from its spec.
#include "capture/camera_sources.hpp"
#include "capture/file_sources.hpp"
#include "horopter/core/error.hpp"
#include "horopter/vision/capture.hpp"

namespace horopter {

namespace {

// "A,B" -> {A, B}; throws when there are not exactly two non-empty parts.
std::pair<std::string, std::string> twoPaths(const std::string& list, const std::string& spec) {
  const auto comma = list.find(',');
  if (comma == std::string::npos || comma == 0 || comma + 1 == list.size() ||
      list.find(',', comma + 1) != std::string::npos)
    throw Error("'" + spec + "' needs two comma-separated parts (left,right)");
  return {list.substr(0, comma), list.substr(comma + 1)};
}

}  // namespace

StereoSource::~StereoSource() = default;

std::unique_ptr<StereoSource> openSource(const std::string& spec, const CaptureOptions& options) {
  const auto colon = spec.find(':');
  const std::string kind = spec.substr(0, colon);
  const std::string rest = colon == std::string::npos ? "" : spec.substr(colon + 1);
  if (kind == "synthetic")
    throw Error(
        "the synthetic scene is the simulator's source: open it with "
        "sim::syntheticSourceOpener (horopter run and the Python module do)");
  if (kind == "dir" && !rest.empty()) return std::make_unique<capture::DirectorySource>(rest);
  if (kind == "video") {
    const auto [l, r] = twoPaths(rest, spec);
    return std::make_unique<capture::VideoPairSource>(l, r);
  }
  if (kind == "camera") {
    const auto [l, r] = twoPaths(rest, spec);
    return std::make_unique<capture::CameraPairSource>(l, r, options);
  }
  if (kind == "sbs" && !rest.empty())
    return std::make_unique<capture::SideBySideSource>(rest, options);
  throw Error("unknown source '" + spec +
              "': use synthetic, dir:PATH, video:LEFT,RIGHT, camera:LEFTDEV,RIGHTDEV or sbs:DEV");
}

}  // namespace horopter
