// Pipeline's keyword arguments, each routed to the option table that
// declares it: the stereo parameters (cv::StereoBM's names) and the tuning
// tables of the detector, the election, the tracker, head control and zone
// search (horopter.tuning_options() lists them).
#pragma once

#include <pybind11/pybind11.h>

#include "horopter/app/pipeline_builder.hpp"

namespace horopter::python {

namespace py = pybind11;

// TypeError for an unknown name (listing the known ones) or a value of the
// wrong type; horopter.Error for a value out of its range.
void applyPipelineKwargs(PipelineConfig& config, const py::kwargs& kwargs);

}  // namespace horopter::python
