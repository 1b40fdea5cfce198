// StereoParams from Python keyword arguments with cv::StereoBM's names.
#pragma once

#include <pybind11/pybind11.h>

#include <string>

#include "horopter/kernels/stereo_params.hpp"

namespace horopter::python {

namespace py = pybind11;

// preFilterType from 'normalized' / 'xsobel' / 'none', OpenCV's ints (0 =
// STEREO_BM_PREFILTER_NORMALIZED_RESPONSE, 1 = STEREO_BM_PREFILTER_XSOBEL; 2 =
// none) or a PreFilterType. horopter.Error for an int out of range, TypeError
// for another type.
PreFilterType preFilterTypeFrom(py::handle value);
// Sets one field by name, range-checked (horopter.Error naming it); TypeError
// for an unknown name (listing the known ones) or a value of the wrong type.
void setStereoField(StereoParams& params, const std::string& name, py::handle value);
// Sets each named field, as setStereoField.
void applyStereoKwargs(StereoParams& params, const py::kwargs& kwargs);
StereoParams stereoParamsFrom(const py::kwargs& kwargs);
std::string repr(const StereoParams& p);

}  // namespace horopter::python
