// Calibration files (written by `horopter calibrate`), the rectified
// geometry they give, and rectification of captured pairs.
#include <mutex>

#include "arrays.hpp"
#include "bindings.hpp"
#include "horopter/calibration.hpp"

namespace horopter::python {

namespace {

// A small matrix as a new float64 array (a copy: calibration matrices are tiny).
py::object matrix(const cv::Mat& m) {
  if (m.empty()) return py::none();
  cv::Mat d;
  m.convertTo(d, CV_64F);
  return shareMat(d);
}

py::tuple rect(const cv::Rect& r) {
  return py::make_tuple(r.x, r.y, r.width, r.height);
}

class Rectifier {
 public:
  explicit Rectifier(const StereoCalibration& c) : rectifier_(c) {}

  py::tuple rectify(py::handle left, py::handle right) {
    const cv::Mat l = matOver(inputView(left, {PixelType::U8C1, PixelType::U8C3}, "left image"));
    const cv::Mat r = matOver(inputView(right, {PixelType::U8C1, PixelType::U8C3}, "right image"));
    cv::Mat outLeft, outRight;
    {
      // The lock only with the GIL released (see StereoMatcher in bind_stereo.cpp).
      py::gil_scoped_release release;
      std::lock_guard lock(mutex_);
      rectifier_.rectify(l, r);
      // The rectifier reuses its buffers on the next call.
      outLeft = rectifier_.left().clone();
      outRight = rectifier_.right().clone();
    }
    return py::make_tuple(shareMat(outLeft), shareMat(outRight));
  }
  py::tuple imageSize() const {
    return py::make_tuple(rectifier_.imageSize().width, rectifier_.imageSize().height);
  }

 private:
  StereoRectifier rectifier_;
  std::mutex mutex_;
};

}  // namespace

void bindCalibration(py::module_& m) {
  py::class_<StereoCalibration>(m, "StereoCalibration",
                                "A stereo calibration (OpenCV's conventions): intrinsics, "
                                "extrinsics, rectification, quality figures")
      .def_property_readonly("image_size",
                             [](const StereoCalibration& c) {
                               return py::make_tuple(c.imageSize.width, c.imageSize.height);
                             })
      .def_property_readonly("K1", [](const StereoCalibration& c) { return matrix(c.K1); })
      .def_property_readonly("D1", [](const StereoCalibration& c) { return matrix(c.D1); })
      .def_property_readonly("K2", [](const StereoCalibration& c) { return matrix(c.K2); })
      .def_property_readonly("D2", [](const StereoCalibration& c) { return matrix(c.D2); })
      .def_property_readonly("R", [](const StereoCalibration& c) { return matrix(c.R); })
      .def_property_readonly("T", [](const StereoCalibration& c) { return matrix(c.T); })
      .def_property_readonly("E", [](const StereoCalibration& c) { return matrix(c.E); })
      .def_property_readonly("F", [](const StereoCalibration& c) { return matrix(c.F); })
      .def_property_readonly("R1", [](const StereoCalibration& c) { return matrix(c.R1); })
      .def_property_readonly("R2", [](const StereoCalibration& c) { return matrix(c.R2); })
      .def_property_readonly("P1", [](const StereoCalibration& c) { return matrix(c.P1); })
      .def_property_readonly("P2", [](const StereoCalibration& c) { return matrix(c.P2); })
      .def_property_readonly("Q", [](const StereoCalibration& c) { return matrix(c.Q); })
      .def_property_readonly("roi1", [](const StereoCalibration& c) { return rect(c.roi1); })
      .def_property_readonly("roi2", [](const StereoCalibration& c) { return rect(c.roi2); })
      .def_readonly("alpha", &StereoCalibration::alpha)
      .def_readonly("rms", &StereoCalibration::rms)
      .def_readonly("rms_left", &StereoCalibration::rmsLeft)
      .def_readonly("rms_right", &StereoCalibration::rmsRight)
      .def_readonly("epipolar_error", &StereoCalibration::epipolarError)
      .def_readonly("homography_error", &StereoCalibration::homographyError)
      .def_property_readonly("views", [](const StereoCalibration& c) {
        py::list out;
        for (const ViewError& v : c.views) {
          py::dict d;
          d["name"] = v.name;
          d["left"] = v.left;
          d["right"] = v.right;
          out.append(d);
        }
        return out;
      });

  m.def("load_calibration", &loadStereoCalibration, py::arg("path"),
        "Reads a calibration file (OpenCV YAML/XML, as `horopter calibrate` writes)");
  m.def("save_calibration", &saveStereoCalibration, py::arg("calibration"), py::arg("path"));
  m.def("rectified_geometry", &rectifiedGeometry, py::arg("calibration"),
        "The RectifiedGeometry of a calibration (f, cx, cy from P1; baseline from P2)");

  py::class_<Rectifier>(m, "StereoRectifier",
                        "Undistort-rectify maps computed once; rectify() remaps a captured pair")
      .def(py::init<const StereoCalibration&>(), py::arg("calibration"))
      .def("rectify", &Rectifier::rectify, py::arg("left"), py::arg("right"),
           "(left, right) rectified, as new arrays")
      .def_property_readonly("image_size", &Rectifier::imageSize);
}

}  // namespace horopter::python
