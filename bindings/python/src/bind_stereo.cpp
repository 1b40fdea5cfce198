// StereoParams and MedianParams with cv::StereoBM's names, and StereoMatcher,
// the per-frame front end (horopter::StereoFrontend).
#include <cctype>
#include <deque>
#include <mutex>
#include <string>

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

  StereoParams params() {
    py::gil_scoped_release release;
    std::lock_guard lock(mutex_);
    return frontend_.stereoParams();
  }

  // Validated with the GIL held; on a bad value the old settings stay.
  void setParams(const StereoParams& p) {
    validate(p);
    py::gil_scoped_release release;
    std::lock_guard lock(mutex_);
    frontend_.setStereoParams(p);
  }

  void setField(const std::string& name, py::handle value) {
    StereoParams p = params();
    setStereoField(p, name, value);
    setParams(p);
  }

  py::object field(const std::string& name) {
    const StereoParams p = params();
    if (name == "preFilterType") return py::cast(p.preFilterType);
    for (const IntOption<StereoParams>& o : stereoOptions())
      if (name == o.name) return py::int_(p.*o.member);
    throw py::attribute_error("no stereo parameter '" + name + "'");
  }

 private:
  StereoFrontend frontend_;
  std::mutex mutex_;
};

// matcher.params: the matcher's own parameters, read and written through, so
// that `matcher.params.numDisparities = 32` takes effect on the next compute
// (validated: a bad value raises and keeps the old settings).
class StereoMatcherParams {
 public:
  explicit StereoMatcherParams(StereoMatcher& matcher) : matcher_(&matcher) {}
  StereoMatcher& matcher() const { return *matcher_; }

 private:
  StereoMatcher* matcher_;  // kept alive by keep_alive on the property
};

// A string that lives as long as the module (pybind11 keeps the pointers of
// names and docstrings it is given).
const char* keep(std::string s) {
  static std::deque<std::string> strings;
  strings.push_back(std::move(s));
  return strings.back().c_str();
}

std::string capitalized(std::string name) {
  name[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(name[0])));
  return name;
}

StereoMatcher* makeMatcher(const py::args& args, const py::kwargs& kwargs) {
  StereoParams stereo;
  MedianParams median;
  std::string backend = FrontendDefaults::backend;
  int threads = FrontendDefaults::threads;
  // Positional: (numDisparities, blockSize) as cv2.StereoBM_create, or the
  // older (params, median, backend, threads).
  const bool paramsFirst =
      args.size() > 0 && (py::isinstance<StereoParams>(args[0]) || args[0].is_none());
  const std::size_t most = paramsFirst ? 4 : 2;
  if (args.size() > most)
    throw py::type_error(
        "StereoMatcher takes at most " + std::to_string(most) + " positional arguments (" +
        (paramsFirst ? "params, median, backend, threads" : "numDisparities, blockSize") +
        "), got " + std::to_string(args.size()));
  py::kwargs fields;
  if (paramsFirst) {
    if (!args[0].is_none()) stereo = args[0].cast<StereoParams>();
    if (args.size() > 1 && !args[1].is_none()) median = args[1].cast<MedianParams>();
    if (args.size() > 2) backend = args[2].cast<std::string>();
    if (args.size() > 3) threads = args[3].cast<int>();
  } else {
    if (args.size() > 0) fields["numDisparities"] = args[0];
    if (args.size() > 1) fields["blockSize"] = args[1];
  }
  for (const auto& [key, value] : kwargs) {
    const std::string name = py::str(key);
    if (name == "params") {
      if (!value.is_none()) stereo = value.cast<StereoParams>();
    } else if (name == "median") {
      if (!value.is_none()) median = value.cast<MedianParams>();
    } else if (name == "backend") {
      backend = value.cast<std::string>();
    } else if (name == "threads") {
      threads = value.cast<int>();
    } else {
      if (fields.contains(key))
        throw py::type_error("StereoMatcher got " + name + " both by position and by name");
      fields[key] = value;
    }
  }
  applyStereoKwargs(stereo, fields);
  return new StereoMatcher(stereo, median, backend, threads);
}

}  // namespace

void bindStereo(py::module_& m) {
  py::enum_<PreFilterType>(m, "PreFilterType",
                           "The matching cost's input, as cv::StereoBM's; the values of its two "
                           "types are OpenCV's (int(PreFilterType.XSOBEL) == 1). Wherever a "
                           "PreFilterType is taken, 0, 1, 2 and 'normalized', 'xsobel', 'none' "
                           "are taken too.")
      .value("NORMALIZED_RESPONSE", PreFilterType::NormalizedResponse,
             "each pixel less its preFilterSize neighbourhood's mean, clipped "
             "(PREFILTER_NORMALIZED_RESPONSE, 0)")
      .value("XSOBEL", PreFilterType::XSobel, "clipped horizontal Sobel (PREFILTER_XSOBEL, 1)")
      .value("NONE", PreFilterType::None, "raw intensities (Horopter's own, 2)");
  // cv2's constants, plain ints as there.
  m.attr("STEREO_BM_PREFILTER_NORMALIZED_RESPONSE") =
      static_cast<int>(PreFilterType::NormalizedResponse);
  m.attr("STEREO_BM_PREFILTER_XSOBEL") = static_cast<int>(PreFilterType::XSobel);

  py::class_<StereoParams> paramsClass(
      m, "StereoParams",
      "cv::StereoBM's parameters, with its names; disparities are int16 in "
      "1/16 px, invalid = (minDisparity - 1) * 16");
  paramsClass
      .def(py::init([](const py::kwargs& kwargs) { return stereoParamsFrom(kwargs); }),
           "StereoParams(**kwargs): any of minDisparity, numDisparities, blockSize, "
           "preFilterType ('normalized', 'xsobel', 'none', 0, 1, 2 or PreFilterType), "
           "preFilterSize, preFilterCap, textureThreshold, uniquenessRatio, disp12MaxDiff, "
           "speckleWindowSize, speckleRange; each within its range (horopter.stereo_options()). "
           "The defaults are Horopter's own; horopter.stereo_bm_defaults() gives "
           "cv::StereoBM's")
      .def_property(
          "preFilterType", [](const StereoParams& p) { return p.preFilterType; },
          [](StereoParams& p, const py::object& v) { p.preFilterType = preFilterTypeFrom(v); },
          "PreFilterType; set from a PreFilterType, 0, 1, 2 or 'normalized', 'xsobel', 'none'")
      .def(
          "validate", [](const StereoParams& p) { validate(p); },
          "Raises horopter.Error naming the first bad parameter")
      .def_property_readonly("invalidDisparity",
                             [](const StereoParams& p) { return invalidDisparity(p); })
      .def("__repr__", [](const StereoParams& p) { return repr(p); });
  m.def(
      "stereo_bm_defaults",
      [](int numDisparities, int blockSize) { return stereoBMDefaults(numDisparities, blockSize); },
      py::arg("numDisparities") = 0, py::arg("blockSize") = 21,
      "StereoParams set as cv::StereoBM_create(numDisparities, blockSize) sets them: 0 "
      "disparities mean 64, XSOBEL prefilter (size 9, cap 31), textureThreshold 10, "
      "uniquenessRatio 15, speckle filter and left-right check off (stereoBMDefaults in "
      "horopter/kernels/stereo_params.hpp)");
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
        [member](StereoParams& p, int v) { p.*member = v; },
        keep(std::string(o.help) + " (" + std::to_string(o.min) + ".." + std::to_string(o.max) +
             (*o.unit ? std::string(" ") + o.unit : std::string()) + ")"));
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

  py::class_<StereoMatcherParams> liveParams(
      m, "StereoMatcherParams",
      "A StereoMatcher's own parameters (matcher.params), read and written through: "
      "assigning a field takes effect on the next compute, validated (horopter.Error naming "
      "the parameter keeps the old settings). copy() gives a detached StereoParams.");
  liveParams
      .def_property(
          "preFilterType",
          [](const StereoMatcherParams& p) { return p.matcher().params().preFilterType; },
          [](const StereoMatcherParams& p, const py::object& v) {
            p.matcher().setField("preFilterType", v);
          },
          "PreFilterType; set from a PreFilterType, 0, 1, 2 or 'normalized', 'xsobel', 'none'")
      .def_property_readonly(
          "invalidDisparity",
          [](const StereoMatcherParams& p) { return invalidDisparity(p.matcher().params()); },
          "the invalid marker, (minDisparity - 1) * 16")
      .def(
          "copy", [](const StereoMatcherParams& p) { return p.matcher().params(); },
          "A detached StereoParams with the matcher's current values")
      .def(
          "validate", [](const StereoMatcherParams& p) { validate(p.matcher().params()); },
          "Raises horopter.Error naming the first bad parameter (never, as setting validates)")
      .def("__repr__", [](const StereoMatcherParams& p) { return repr(p.matcher().params()); });
  for (const IntOption<StereoParams>& o : stereoOptions()) {
    const std::string name = o.name;
    liveParams.def_property(
        o.name,
        [name](const StereoMatcherParams& p) { return p.matcher().field(name).cast<int>(); },
        [name](const StereoMatcherParams& p, const py::object& v) {
          p.matcher().setField(name, v);
        },
        keep(std::string(o.help) + " (" + std::to_string(o.min) + ".." + std::to_string(o.max) +
             (*o.unit ? std::string(" ") + o.unit : std::string()) +
             "); assigning it sets the matcher"));
  }

  py::class_<StereoMatcher> matcherClass(
      m, "StereoMatcher",
      "The front end: prefilter, SAD matching, left-right check, speckles, hole-filling "
      "median, horopter mask. Inputs are read in place; results are new arrays. Shaped like "
      "cv2.StereoBM: compute(left, right), getX()/setX(v) for each StereoBM parameter "
      "(horopter.StereoBM_create gives one set up as cv2.StereoBM_create).");
  matcherClass
      .def(py::init(&makeMatcher),
           "StereoMatcher(numDisparities=None, blockSize=None, *, params=None, median=None, "
           "backend='auto', threads=0, **kwargs), or StereoMatcher(params, median=None, "
           "backend='auto', threads=0). Unset fields take Horopter's StereoParams defaults "
           "(numDisparities 64, blockSize 9, ...); kwargs are StereoParams fields. "
           "backend 'auto' and threads 0 (every hardware thread) are the library's defaults, "
           "the same as the C API's and the CLI's")
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
      .def_property(
          "params", [](StereoMatcher& s) { return StereoMatcherParams(s); },
          [](StereoMatcher& s, const py::object& v) {
            if (py::isinstance<StereoMatcherParams>(v))
              s.setParams(v.cast<const StereoMatcherParams&>().matcher().params());
            else
              s.setParams(v.cast<StereoParams>());
          },
          py::keep_alive<0, 1>(),
          "The matcher's parameters, live (StereoMatcherParams): reading gives the current "
          "values, assigning a field or a whole StereoParams sets them for the next compute, "
          "validated")
      .def_property_readonly("median",
                             [](const StereoMatcher& s) { return s.frontend().medianParams(); })
      .def_property_readonly("timings", &StereoMatcher::timings,
                             "milliseconds of each stage of the last frame")
      .def(
          "getPreFilterType",
          [](StereoMatcher& s) { return static_cast<int>(s.params().preFilterType); },
          "preFilterType as cv2 gives it: STEREO_BM_PREFILTER_NORMALIZED_RESPONSE (0), "
          "STEREO_BM_PREFILTER_XSOBEL (1), or 2 for none")
      .def(
          "setPreFilterType",
          [](StereoMatcher& s, const py::object& v) { s.setField("preFilterType", v); },
          py::arg("preFilterType"),
          "Sets preFilterType (0, 1, 2, 'normalized', 'xsobel', 'none' or a PreFilterType) for "
          "the next compute; a bad value raises and keeps the old one");
  // getX / setX for each integer parameter, from its table (as cv2.StereoBM's).
  for (const IntOption<StereoParams>& o : stereoOptions()) {
    const std::string name = o.name;
    const std::string range = std::to_string(o.min) + ".." + std::to_string(o.max) +
                              (*o.unit ? std::string(" ") + o.unit : std::string());
    matcherClass.def(
        keep("get" + capitalized(name)),
        [name](StereoMatcher& s) { return s.field(name).cast<int>(); },
        keep(name + ": " + o.help + " (" + range + ")"));
    matcherClass.def(
        keep("set" + capitalized(name)),
        [name](StereoMatcher& s, const py::object& v) { s.setField(name, v); }, py::arg(keep(name)),
        keep("Sets " + name + " (" + o.help + ", " + range +
             ") for the next compute; a bad value raises horopter.Error naming it and keeps the "
             "old settings"));
  }

  m.def(
      "StereoBM_create",
      [](int numDisparities, int blockSize) {
        return new StereoMatcher(stereoBMDefaults(numDisparities, blockSize), MedianParams{0, 0},
                                 FrontendDefaults::backend, FrontendDefaults::threads);
      },
      py::arg("numDisparities") = 0, py::arg("blockSize") = 21,
      py::return_value_policy::take_ownership,
      "A StereoMatcher set up as cv2.StereoBM_create(numDisparities, blockSize): StereoBM's "
      "defaults (0 disparities mean 64, XSOBEL prefilter, textureThreshold 10, "
      "uniquenessRatio 15, speckle filter and left-right check off), no median; the library's "
      "default backend and threads");
}

}  // namespace horopter::python
