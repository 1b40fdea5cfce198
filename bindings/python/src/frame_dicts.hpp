// What Python sees of a pipeline frame and of the synthetic scene's truth:
// numpy arrays sharing the frame's memory, and plain dicts.
#pragma once

#include <pybind11/pybind11.h>

#include "horopter/app/frame.hpp"
#include "horopter/interaction/body.hpp"
#include "horopter/movement/movement.hpp"
#include "horopter/sim/synthetic_scene.hpp"

namespace horopter::python {

namespace py = pybind11;

py::dict bodyDict(const BodySample& body);
// The inverse, for tracks built in Python: KeyError/TypeError for a bad dict.
BodySample bodyFromDict(py::handle dict);
// likeliest, posterior {name: p}, decision (a name or None), action,
// action_started, interaction_stopped, features_valid.
py::dict movementDict(const MovementState& state);
py::dict truthDict(const synth::FrameTruth& truth);
// index, time_s, left, right, left_grey, right_grey, disparity, thresholds,
// mask, body, truth (synthetic sources), and detections, tracking and
// movement (dicts when those stages ran, else None).
py::dict frameDict(const Frame& frame);

}  // namespace horopter::python
