// The geometry of the zone of interaction: fixation points, the
// Vieth-Mueller circle, depth, and the per-column threshold table.
// 3-D points are numpy float64 arrays of 3 (cyclopean frame).
#include <pybind11/eigen.h>

#include "arrays.hpp"
#include "bindings.hpp"
#include "horopter/vision/geometry.hpp"

namespace horopter::python {

namespace {

py::array_t<std::int16_t> thresholdsForCircle(const RectifiedGeometry& g,
                                              const ViethMuellerCircle& circle, int width) {
  if (width <= 0) throw py::value_error("width must be positive, got " + std::to_string(width));
  py::array_t<std::int16_t> out(width);
  horopterThresholds(g, circle, {out.mutable_data(), static_cast<std::size_t>(width)});
  return out;
}

py::array_t<std::int16_t> thresholdsForFixation(const RectifiedGeometry& g, int width,
                                                const FixationPoint& fixation) {
  const std::vector<std::int16_t> table = horopterThresholds(g, width, fixation);
  py::array_t<std::int16_t> out(static_cast<py::ssize_t>(table.size()));
  std::copy(table.begin(), table.end(), out.mutable_data());
  return out;
}

}  // namespace

void bindGeometry(py::module_& m) {
  py::class_<RectifiedGeometry>(m, "RectifiedGeometry",
                                "A rectified pair: focal length and principal point (px), "
                                "baseline (any length unit)")
      .def(py::init([](double focalPx, double cx, double baseline, double cy) {
             return RectifiedGeometry{focalPx, cx, baseline, cy};
           }),
           py::arg("focal_px"), py::arg("cx"), py::arg("baseline"), py::arg("cy") = 0.0)
      .def_readwrite("focal_px", &RectifiedGeometry::focalPx)
      .def_readwrite("cx", &RectifiedGeometry::cx)
      .def_readwrite("cy", &RectifiedGeometry::cy)
      .def_readwrite("baseline", &RectifiedGeometry::baseline)
      .def("__repr__", [](const RectifiedGeometry& g) {
        return "RectifiedGeometry(focal_px=" + std::to_string(g.focalPx) +
               ", cx=" + std::to_string(g.cx) + ", baseline=" + std::to_string(g.baseline) +
               ", cy=" + std::to_string(g.cy) + ")";
      });

  py::class_<FixationPoint>(m, "FixationPoint", "A fixation in the left camera frame")
      .def(py::init([](double x, double z) {
             return FixationPoint{x, z};
           }),
           py::arg("x"), py::arg("z"))
      .def_readwrite("x", &FixationPoint::x)
      .def_readwrite("z", &FixationPoint::z);

  py::class_<ViethMuellerCircle>(m, "ViethMuellerCircle",
                                 "The circle through both camera centres and the fixation")
      .def_readonly("centre_z", &ViethMuellerCircle::centreZ)
      .def_readonly("radius", &ViethMuellerCircle::radius)
      .def_property_readonly(
          "fixation", [](const ViethMuellerCircle& c) { return Eigen::Vector2d(c.fixation); });

  m.def("fixation_from_disparity", &fixationFromDisparity, py::arg("geometry"), py::arg("u"),
        py::arg("disparity_px"), "The fixation seen at column u with this disparity (px)");
  m.def("fixation_from_vergence", &fixationFromVergence, py::arg("baseline"),
        py::arg("vergence_rad"),
        "The fixation (x, y, z) of a symmetric vergence: each camera turned inward by half of "
        "vergence_rad (0 < vergence_rad < pi); on the head's axis");
  m.def("fixation_from_pan_angles", &fixationFromPanAngles, py::arg("baseline"),
        py::arg("left_pan_rad"), py::arg("right_pan_rad"),
        "The fixation (x, y, z) where the optical axes cross, from each camera's pan (rad from "
        "+z, positive towards +x); they cross in front only when left_pan_rad > right_pan_rad");
  m.def("fixation_at_distance", &fixationAtDistance, py::arg("baseline"), py::arg("distance"),
        "The fixation (x, y, z) straight ahead at z = distance: the zone reaches exactly that "
        "far on the head's axis");
  m.def("vieth_mueller_circle", &viethMuellerCircle, py::arg("baseline"), py::arg("fixation"),
        "The circle through both camera centres (-B/2, 0), (B/2, 0) and the fixation's (x, z)");
  m.def("inside_zone", &insideZone, py::arg("circle"), py::arg("point"),
        "True when the 3-D point is strictly inside the circle in (x, z) and in front of the "
        "baseline (z > 0)");
  m.def("vergence_angle_at", &vergenceAngleAt, py::arg("baseline"), py::arg("point"),
        "The vergence angle (rad) a 3-D point subtends between the two camera centres");
  m.def("depth_from_disparity", &depthFromDisparity, py::arg("geometry"), py::arg("disparity_px"),
        "z = f B / d");
  m.def("point_from_pixel", &pointFromPixel, py::arg("geometry"), py::arg("u"), py::arg("v"),
        py::arg("disparity_px"), "The 3-D point (cyclopean frame) of a left pixel");
  m.def("to_left_camera_frame", &toLeftCameraFrame, py::arg("geometry"), py::arg("point"),
        "A 3-D point of the cyclopean frame as a FixationPoint in the left camera's frame, for "
        "horopter_thresholds");
  m.def("horopter_thresholds", &thresholdsForFixation, py::arg("geometry"), py::arg("width"),
        py::arg("fixation"),
        "int16 (width,): per column, the smallest disparity (1/16 px) inside the zone");
  m.def("horopter_thresholds", &thresholdsForCircle, py::arg("geometry"), py::arg("circle"),
        py::arg("width"),
        "int16 (width,): the same table for a circle (vieth_mueller_circle), cheap enough for "
        "every frame");
  m.def(
      "zone_extent",
      [](double baseline, const ViethMuellerCircle& circle) {
        const ZoneExtent e = zoneExtent(baseline, circle);
        py::dict d;
        d["radius"] = e.radius;
        d["centre_z"] = e.centreZ;
        d["far_on_axis"] = e.farOnAxis;
        d["far_on_camera"] = e.farOnCamera;
        d["widest_z"] = e.widestZ;
        d["widest"] = e.widest;
        return d;
      },
      py::arg("baseline"), py::arg("circle"),
      "How far the zone reaches: a dict of radius, centre_z, far_on_axis, far_on_camera, "
      "widest_z (depth of the widest chord) and widest (its width)");
  m.def("zone_width_at", &zoneWidthAt, py::arg("circle"), py::arg("z"),
        "Width of the zone (the circle's chord parallel to the baseline) at depth z; 0 where "
        "the plane misses the circle");
}

}  // namespace horopter::python
