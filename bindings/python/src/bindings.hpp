// The parts of the `horopter` module, each added by its own file.
#pragma once

#include <pybind11/pybind11.h>

namespace horopter::python {

namespace py = pybind11;

void bindStereo(py::module_& m);       // StereoParams, MedianParams, StereoMatcher
void bindKernels(py::module_& m);      // each front-end kernel
void bindSystem(py::module_& m);       // backends, devices, image files
void bindGeometry(py::module_& m);     // circle, fixation, threshold table, depth
void bindCalibration(py::module_& m);  // calibration files, rectification
void bindScene(py::module_& m);        // the synthetic stereo scene
void bindPipeline(py::module_& m);     // the frame pipeline, iterated from Python
void bindMovement(py::module_& m);     // the movement classifier, body tracks
void bindEval(py::module_& m);         // Table III one trial at a time, and its summary

}  // namespace horopter::python
