#include "pipeline_args.hpp"

#include <span>
#include <string>

#include "horopter/core/option_table.hpp"
#include "stereo_args.hpp"

namespace horopter::python {

namespace {

// Sets `name` in p when the table declares it; false when it does not.
template <class Params>
bool setTuningOption(std::span<const NumberOption<Params>> table, Params& p,
                     const std::string& name, const py::handle& value) {
  for (const NumberOption<Params>& o : table) {
    if (name != o.name) continue;
    const bool isInt = py::isinstance<py::int_>(value) && !py::isinstance<py::bool_>(value);
    const bool isNumber = isInt || py::isinstance<py::float_>(value);
    if (o.integer() ? !isInt : !isNumber)
      throw py::type_error(name + (o.integer() ? " must be an int" : " must be a number") +
                           ", got " + std::string(py::str(py::type::of(value).attr("__name__"))));
    const double v = value.cast<double>();
    if (!(v >= o.min && v <= o.max))
      throw Error(numberRangeMessage(o.name, o.unit, o.min, o.max, v));
    o.set(p, v);
    return true;
  }
  return false;
}

template <class Params>
void listNames(std::span<const NumberOption<Params>> table, std::string& out) {
  for (const NumberOption<Params>& o : table)
    out += std::string(", ") + o.name;
}

bool isStereoName(const std::string& name) {
  if (name == "preFilterType") return true;
  for (const IntOption<StereoParams>& o : stereoOptions())
    if (name == o.name) return true;
  return false;
}

}  // namespace

void applyPipelineKwargs(PipelineConfig& c, const py::kwargs& kwargs) {
  py::kwargs stereo;
  for (const auto& [key, value] : kwargs) {
    const std::string name = py::str(key);
    if (isStereoName(name)) {
      stereo[key] = value;
      continue;
    }
    if (setTuningOption(detectorOptions(), c.detector, name, value) ||
        setTuningOption(electionOptions(), c.tracker.election, name, value) ||
        setTuningOption(trackerOptions(), c.tracker, name, value) ||
        setTuningOption(headControlOptions(), c.head, name, value) ||
        setTuningOption(zoneSearchOptions(), c.zoneSearch, name, value))
      continue;
    std::string known = "preFilterType";
    for (const IntOption<StereoParams>& o : stereoOptions())
      known += std::string(", ") + o.name;
    listNames(detectorOptions(), known);
    listNames(electionOptions(), known);
    listNames(trackerOptions(), known);
    listNames(headControlOptions(), known);
    listNames(zoneSearchOptions(), known);
    throw py::type_error("unknown Pipeline option '" + name + "': use one of " + known);
  }
  applyStereoKwargs(c.stereo, stereo);
}

}  // namespace horopter::python
