// The `horopter` Python module. Kernels and the front end release the GIL
// while they run, so several Python threads compute at once.
#include <pybind11/pybind11.h>

#include "bindings.hpp"
#include "horopter/core/error.hpp"
#include "horopter/version.h"

PYBIND11_MODULE(horopter, m) {
  namespace py = pybind11;
  m.doc() =
      "Horopter: stereo disparity (OpenCV StereoBM's parameters), the horopter mask of the zone "
      "of interaction, calibration, geometry and the frame pipeline, on numpy arrays without "
      "copying the inputs. STEREO_BM_PREFILTER_NORMALIZED_RESPONSE (0) and "
      "STEREO_BM_PREFILTER_XSOBEL (1) are cv2's StereoBM prefilter constants.";
  // horopter::Error (bad input or a failed operation, with a message that
  // says what to fix) becomes horopter.Error, a ValueError.
  py::register_exception<horopter::Error>(m, "Error", PyExc_ValueError).attr("__doc__") =
      "Bad input or a failed operation, with a message that says what to fix (a ValueError)";
  m.attr("__version__") = HOROPTER_VERSION_STRING;  // horopter/version.h
  horopter::python::bindStereo(m);
  horopter::python::bindKernels(m);
  horopter::python::bindSystem(m);
  horopter::python::bindGeometry(m);
  horopter::python::bindCalibration(m);
  horopter::python::bindScene(m);
  horopter::python::bindPipeline(m);
  horopter::python::bindMovement(m);
  horopter::python::bindEval(m);
}
