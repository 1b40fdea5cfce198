#include "stereo_args.hpp"

#include <utility>
#include <vector>

namespace horopter::python {

namespace {

using IntField = std::pair<const char*, int StereoParams::*>;
const std::vector<IntField>& intFields() {
  static const std::vector<IntField> fields = {
      {"minDisparity", &StereoParams::minDisparity},
      {"numDisparities", &StereoParams::numDisparities},
      {"blockSize", &StereoParams::blockSize},
      {"preFilterCap", &StereoParams::preFilterCap},
      {"textureThreshold", &StereoParams::textureThreshold},
      {"uniquenessRatio", &StereoParams::uniquenessRatio},
      {"disp12MaxDiff", &StereoParams::disp12MaxDiff},
      {"speckleWindowSize", &StereoParams::speckleWindowSize},
      {"speckleRange", &StereoParams::speckleRange},
  };
  return fields;
}

}  // namespace

void applyStereoKwargs(StereoParams& params, const py::kwargs& kwargs) {
  for (const auto& [key, value] : kwargs) {
    const std::string name = py::str(key);
    if (name == "preFilterType") {
      if (py::isinstance<py::str>(value))
        params.preFilterType = parsePreFilterType(value.cast<std::string>());
      else
        params.preFilterType = value.cast<PreFilterType>();
      continue;
    }
    bool found = false;
    for (const auto& [field, member] : intFields()) {
      if (name != field) continue;
      if (!py::isinstance<py::int_>(value))
        throw py::type_error(name + " must be an int, got " +
                             std::string(py::str(py::type::of(value).attr("__name__"))));
      params.*member = value.cast<int>();
      found = true;
    }
    if (!found) {
      std::string known = "preFilterType";
      for (const auto& [field, member] : intFields())
        known += std::string(", ") + field;
      throw py::type_error("unknown stereo parameter '" + name + "': use one of " + known);
    }
  }
}

StereoParams stereoParamsFrom(const py::kwargs& kwargs) {
  StereoParams p;
  applyStereoKwargs(p, kwargs);
  return p;
}

std::string repr(const StereoParams& p) {
  std::string s = "StereoParams(";
  for (const auto& [field, member] : intFields())
    s += std::string(field) + "=" + std::to_string(p.*member) + ", ";
  return s + "preFilterType='" + toString(p.preFilterType) + "')";
}

}  // namespace horopter::python
