#include "stereo_args.hpp"

#include "horopter/core/error.hpp"
#include "horopter/core/option_table.hpp"

namespace horopter::python {

namespace {

std::string typeName(py::handle value) {
  return py::str(py::type::of(value).attr("__name__"));
}

std::string knownNames() {
  std::string known = "preFilterType";
  for (const IntOption<StereoParams>& o : stereoOptions())
    known += std::string(", ") + o.name;
  return known;
}

}  // namespace

PreFilterType preFilterTypeFrom(py::handle value) {
  if (py::isinstance<py::str>(value)) return parsePreFilterType(value.cast<std::string>());
  if (py::isinstance<PreFilterType>(value)) return value.cast<PreFilterType>();
  if (py::isinstance<py::int_>(value) && !py::isinstance<py::bool_>(value)) {
    const long long v = value.cast<long long>();
    if (v < 0 || v > 2)
      throw Error(
          "preFilterType must be 0 (STEREO_BM_PREFILTER_NORMALIZED_RESPONSE), 1 "
          "(STEREO_BM_PREFILTER_XSOBEL) or 2 (none), got " +
          std::to_string(v));
    return static_cast<PreFilterType>(v);
  }
  throw py::type_error(
      "preFilterType must be 'normalized', 'xsobel', 'none', 0, 1, 2 or a PreFilterType, got " +
      typeName(value));
}

void setStereoField(StereoParams& params, const std::string& name, py::handle value) {
  if (name == "preFilterType") {
    params.preFilterType = preFilterTypeFrom(value);
    return;
  }
  for (const IntOption<StereoParams>& o : stereoOptions()) {
    if (name != o.name) continue;
    if (!py::isinstance<py::int_>(value) || py::isinstance<py::bool_>(value))
      throw py::type_error(name + " must be an int, got " + typeName(value));
    const long long v = value.cast<long long>();
    if (v < o.min || v > o.max) throw Error(rangeMessage(o.name, o.unit, o.min, o.max, v));
    params.*o.member = static_cast<int>(v);
    return;
  }
  throw py::type_error("unknown stereo parameter '" + name + "': use one of " + knownNames());
}

void applyStereoKwargs(StereoParams& params, const py::kwargs& kwargs) {
  for (const auto& [key, value] : kwargs)
    setStereoField(params, py::str(key), value);
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
