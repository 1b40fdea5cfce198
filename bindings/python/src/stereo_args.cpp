#include "stereo_args.hpp"

#include "horopter/core/error.hpp"
#include "horopter/core/option_table.hpp"

namespace horopter::python {

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
    for (const IntOption<StereoParams>& o : stereoOptions()) {
      if (name != o.name) continue;
      if (!py::isinstance<py::int_>(value) || py::isinstance<py::bool_>(value))
        throw py::type_error(name + " must be an int, got " +
                             std::string(py::str(py::type::of(value).attr("__name__"))));
      const long long v = value.cast<long long>();
      if (v < o.min || v > o.max) throw Error(rangeMessage(o.name, o.unit, o.min, o.max, v));
      params.*o.member = static_cast<int>(v);
      found = true;
    }
    if (!found) {
      std::string known = "preFilterType";
      for (const IntOption<StereoParams>& o : stereoOptions())
        known += std::string(", ") + o.name;
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
  for (const IntOption<StereoParams>& o : stereoOptions())
    s += std::string(o.name) + "=" + std::to_string(p.*o.member) + ", ";
  return s + "preFilterType='" + toString(p.preFilterType) + "')";
}

}  // namespace horopter::python
