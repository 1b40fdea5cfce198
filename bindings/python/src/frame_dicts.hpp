// What Python sees of a pipeline frame and of the synthetic scene's truth:
// numpy arrays sharing the frame's memory, and plain dicts.
#pragma once

#include <pybind11/pybind11.h>

#include "horopter/body.hpp"
#include "horopter/pipeline.hpp"
#include "horopter/synthetic_scene.hpp"

namespace horopter::python {

namespace py = pybind11;

py::dict bodyDict(const BodySample& body);
py::dict truthDict(const synth::FrameTruth& truth);
// index, time_s, left, right, left_grey, right_grey, disparity, thresholds,
// mask, body, truth (synthetic sources), and detections / tracking /
// movement (None until those stages exist).
py::dict frameDict(const Frame& frame);

}  // namespace horopter::python
