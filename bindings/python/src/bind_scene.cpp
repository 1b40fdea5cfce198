// The built-in synthetic stereo scene: rectified pairs with exact truth.
#include "arrays.hpp"
#include "bindings.hpp"
#include "frame_dicts.hpp"
#include "horopter/sim/synthetic_scene.hpp"
#include "horopter/vision/geometry.hpp"

namespace horopter::python {

void bindScene(py::module_& m) {
  using synth::SyntheticScene;
  py::class_<SyntheticScene>(m, "SyntheticScene",
                             "A textured room with two people seen by a verging stereo head, "
                             "rendered rectified, with exact disparity and zone truth")
      .def(py::init([](int width, int height, std::uint64_t seed, bool distractor, double fps,
                       double baselineM, double focalPx) {
             synth::SceneOptions o;
             o.width = width;
             o.height = height;
             o.seed = seed;
             o.distractor = distractor;
             o.framesPerSecond = fps;
             o.baselineM = baselineM;
             o.focalPx = focalPx;
             return std::make_unique<SyntheticScene>(o);
           }),
           py::kw_only(), py::arg("width") = 640, py::arg("height") = 480, py::arg("seed") = 1,
           py::arg("distractor") = true, py::arg("fps") = 30.0, py::arg("baseline_m") = 0.12,
           py::arg("focal_px") = 0.0)
      .def(
          "render",
          [](SyntheticScene& scene, int index) {
            // The scene keeps caches: it renders with the GIL held, one call at a time.
            const synth::SyntheticFrame f = scene.render(index);
            py::dict d;
            d["left"] = shareMat(f.left);
            d["right"] = shareMat(f.right);
            d["truth"] = truthDict(f.truth);
            return d;
          },
          py::arg("index"), "{'left', 'right' (uint8 BGR, rectified), 'truth': dict}")
      .def(
          "command_head",
          [](SyntheticScene& scene, double pan, double tilt, double vergence) {
            scene.commandHead({pan, tilt, vergence});
          },
          py::arg("pan"), py::arg("tilt"), py::arg("vergence"), "Turns the head (radians)")
      .def_property_readonly("focal_px", &SyntheticScene::focalPx)
      .def_property_readonly("baseline_m", &SyntheticScene::baselineM)
      .def_property_readonly("cx", &SyntheticScene::cx)
      .def_property_readonly("cy", &SyntheticScene::cy)
      .def_property_readonly("geometry", [](const SyntheticScene& s) {
        return RectifiedGeometry{s.focalPx(), s.cx(), s.baselineM(), s.cy()};
      });
}

}  // namespace horopter::python
