// StereoParams and MedianParams with cv::StereoBM's names, and StereoMatcher,
// the per-frame front end (horopter::StereoFrontend).
#include <mutex>

#include "arrays.hpp"
#include "bindings.hpp"
#include "horopter/interaction/detection.hpp"
#include "horopter/interaction/godfather.hpp"
#include "horopter/interaction/head_control.hpp"
#include "horopter/interaction/tracking.hpp"
#include "horopter/vision/frontend.hpp"
#include "stereo_args.hpp"

namespace horopter::python {

namespace {

// A tuning table as a list of dicts, the way stereo_options() lists its own.
template <class Params>
py::list tuningTable(std::span<const NumberOption<Params>> table, const Params& defaults) {
  py::list out;
  for (const NumberOption<Params>& o : table) {
    py::dict d;
    d["name"] = o.name;
    d["flag"] = o.flag;
    d["unit"] = o.unit;
    d["min"] = o.min;
    d["max"] = o.max;
    d["integer"] = o.integer();
    d["default"] = o.get(defaults);
    d["help"] = o.help;
    out.append(d);
  }
  return out;
}

// One front end per matcher. The lock makes concurrent calls on the same
// matcher wait their turn (the front end reuses its buffers); it is only ever
// taken with the GIL released, so a thread waiting for it never holds the
// GIL that the thread inside needs to hand back its result.
class StereoMatcher {
 public:
  StereoMatcher(const StereoParams& stereo, const MedianParams& median, const std::string& backend,
                int threads)
      : frontend_(stereo, median, findBackend(backend), threads) {}

  py::object compute(py::handle left, py::handle right) {
    const ConstImageView l = inputView(left, {PixelType::U8C1}, "left image");
    const ConstImageView r = inputView(right, {PixelType::U8C1}, "right image");
    py::object out;
    py::gil_scoped_release release;
    std::lock_guard lock(mutex_);
    frontend_.computeDisparity(l, r);
    py::gil_scoped_acquire acquire;
    out = copyOf(frontend_.disparity());
    return out;
  }

  py::object computeMask(py::handle thresholds, py::handle image) {
    const auto table = int16Span(thresholds, "thresholds");
    const ConstImageView view = image.is_none()
                                    ? ConstImageView{}
                                    : inputView(image, {PixelType::U8C1, PixelType::U8C3}, "image");
    py::object out;
    py::gil_scoped_release release;
    std::lock_guard lock(mutex_);
    frontend_.computeMask(table, view);
    py::gil_scoped_acquire acquire;
    // Without an image the front end keeps an older segmented image: None instead.
    out = py::make_tuple(copyOf(frontend_.mask()),
                         image.is_none() ? py::object(py::none()) : copyOf(frontend_.segmented()));
    return out;
  }

  py::dict timings() {
    FrontendTimings t;
    {
      py::gil_scoped_release release;
      std::lock_guard lock(mutex_);
      t = frontend_.timings();
    }
    py::dict d;
    d["prefilter"] = t.prefilter;
    d["match"] = t.match;
    d["cleanup"] = t.cleanup;
    d["median"] = t.median;
    d["mask"] = t.mask;
    d["total"] = t.total();
    return d;
  }

  const StereoFrontend& frontend() const { return frontend_; }

 private:
  StereoFrontend frontend_;
  std::mutex mutex_;
};

}  // namespace

void bindStereo(py::module_& m) {
  py::enum_<PreFilterType>(m, "PreFilterType", "The matching cost's input, as cv::StereoBM's")
      .value("NONE", PreFilterType::None, "raw intensities")
      .value("XSOBEL", PreFilterType::XSobel, "clipped horizontal Sobel (PREFILTER_XSOBEL)");

  py::class_<StereoParams> paramsClass(
      m, "StereoParams",
      "cv::StereoBM's parameters, with its names; disparities are int16 in "
      "1/16 px, invalid = (minDisparity - 1) * 16");
  paramsClass
      .def(py::init([](const py::kwargs& kwargs) { return stereoParamsFrom(kwargs); }),
           "StereoParams(**kwargs): any of minDisparity, numDisparities, blockSize, "
           "preFilterType ('xsobel', 'none' or PreFilterType), preFilterCap, textureThreshold, "
           "uniquenessRatio, disp12MaxDiff, speckleWindowSize, speckleRange; each within its "
           "range (horopter.stereo_options())")
      .def_readwrite("preFilterType", &StereoParams::preFilterType)
      .def(
          "validate", [](const StereoParams& p) { validate(p); },
          "Raises horopter.Error naming the first bad parameter")
      .def_property_readonly("invalidDisparity",
                             [](const StereoParams& p) { return invalidDisparity(p); })
      .def("__repr__", [](const StereoParams& p) { return repr(p); });
  m.def(
      "stereo_options",
      [] {
        const StereoParams defaults;
        py::list out;
        for (const IntOption<StereoParams>& o : stereoOptions()) {
          py::dict d;
          d["name"] = o.name;
          d["flag"] = o.flag;
          d["unit"] = o.unit;
          d["min"] = o.min;
          d["max"] = o.max;
          d["default"] = defaults.*o.member;
          d["help"] = o.help;
          out.append(d);
        }
        return out;
      },
      "The integer stereo parameters as declared once in the library: name, CLI flag, unit, "
      "range, default, help");
  m.def(
      "tuning_options",
      [] {
        const DetectorOptions detector;
        const ElectionOptions election;
        const TrackerOptions tracker;
        const HeadControlOptions head;
        const ZoneSearch zone;
        py::dict out;
        out["detector"] = tuningTable(detectorOptions(), detector);
        out["election"] = tuningTable(electionOptions(), election);
        out["tracker"] = tuningTable(trackerOptions(), tracker);
        out["head_control"] = tuningTable(headControlOptions(), head);
        out["zone_search"] = tuningTable(zoneSearchOptions(), zone);
        return out;
      },
      "The detector's, election's, tracker's, head control's and zone search's tuning options "
      "as declared once in the library: name, CLI flag, unit, range, default, help; "
      "Pipeline takes each by name");
  // The integer parameters from their table (horopter/kernels/stereo_params.hpp).
  for (const IntOption<StereoParams>& o : stereoOptions()) {
    const auto member = o.member;
    paramsClass.def_property(
        o.name, [member](const StereoParams& p) { return p.*member; },
        [member](StereoParams& p, int v) { p.*member = v; });
  }

  py::class_<MedianParams>(m, "MedianParams", "The hole-filling median after matching")
      .def(py::init([](int kernelSize, int minValidToFill) {
             return MedianParams{kernelSize, minValidToFill};
           }),
           py::kw_only(), py::arg("kernelSize") = MedianParams{}.kernelSize,
           py::arg("minValidToFill") = MedianParams{}.minValidToFill)
      .def_readwrite("kernelSize", &MedianParams::kernelSize, "0 (off), 3 or 5")
      .def_readwrite("minValidToFill", &MedianParams::minValidToFill,
                     "valid pixels needed to fill a hole; 0 = more than half the window")
      .def("validate", [](const MedianParams& p) { validate(p); })
      .def("__repr__", [](const MedianParams& p) {
        return "MedianParams(kernelSize=" + std::to_string(p.kernelSize) +
               ", minValidToFill=" + std::to_string(p.minValidToFill) + ")";
      });

  py::class_<StereoMatcher>(m, "StereoMatcher",
                            "The front end: prefilter, SAD matching, left-right check, speckles, "
                            "hole-filling median, horopter mask. Inputs are read in place; "
                            "results are new arrays.")
      .def(py::init([](const py::object& params, const py::object& median,
                       const std::string& backend, int threads, const py::kwargs& kwargs) {
             StereoParams stereo = params.is_none() ? StereoParams{} : params.cast<StereoParams>();
             applyStereoKwargs(stereo, kwargs);
             const MedianParams med =
                 median.is_none() ? MedianParams{} : median.cast<MedianParams>();
             return std::make_unique<StereoMatcher>(stereo, med, backend, threads);
           }),
           py::arg("params") = py::none(), py::arg("median") = py::none(),
           py::arg("backend") = "auto", py::arg("threads") = 1,
           "StereoMatcher(params=None, median=None, backend='auto', threads=1, **kwargs): "
           "kwargs are StereoParams fields (numDisparities=64, blockSize=9, ...)")
      .def("compute", &StereoMatcher::compute, py::arg("left"), py::arg("right"),
           "Disparity (int16, 1/16 px) of a rectified uint8 (H, W) pair")
      .def("compute_mask", &StereoMatcher::computeMask, py::arg("thresholds"),
           py::arg("image") = py::none(),
           "(mask, segmented) of the last disparity: thresholds is int16 (W,), one per column "
           "(horopter_thresholds); segmented is None without an image")
      .def_property_readonly("backend",
                             [](const StereoMatcher& s) { return s.frontend().backend().name; })
      .def_property_readonly("threads",
                             [](const StereoMatcher& s) { return s.frontend().threads(); })
      .def_property_readonly("params",
                             [](const StereoMatcher& s) { return s.frontend().stereoParams(); })
      .def_property_readonly("median",
                             [](const StereoMatcher& s) { return s.frontend().medianParams(); })
      .def_property_readonly("timings", &StereoMatcher::timings,
                             "milliseconds of each stage of the last frame");
}

}  // namespace horopter::python
