// StereoParams from Python keyword arguments with cv::StereoBM's names.
#pragma once

#include <pybind11/pybind11.h>

#include <string>

#include "horopter/kernels/stereo_params.hpp"

namespace horopter::python {

namespace py = pybind11;

// Sets each named field; TypeError for an unknown name (listing the known
// ones). preFilterType takes 'xsobel', 'none' or a PreFilterType.
void applyStereoKwargs(StereoParams& params, const py::kwargs& kwargs);
StereoParams stereoParamsFrom(const py::kwargs& kwargs);
std::string repr(const StereoParams& p);

}  // namespace horopter::python
