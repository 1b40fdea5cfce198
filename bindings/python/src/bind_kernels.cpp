// Each front-end kernel on numpy arrays: inputs read in place, outputs
// written straight into new arrays (or the caller's, in place), the GIL
// released while the kernel runs.
#include "arrays.hpp"
#include "bindings.hpp"
#include "horopter/kernels/kernels.hpp"

namespace horopter::python {

namespace {

const Backend& backendNamed(const std::string& name) {
  return findBackend(name);
}

py::tuple prefilter(py::handle src, int cap, const std::string& backend) {
  const ConstImageView in = inputView(src, {PixelType::U8C1}, "src");
  const Backend& b = backendNamed(backend);
  py::array filtered = newImage(in.width, in.height, PixelType::U8C1);
  py::array texture = newImage(in.width, in.height, PixelType::U8C1);
  const ImageView f = outputView(filtered, PixelType::U8C1, "filtered");
  const ImageView t = outputView(texture, PixelType::U8C1, "texture");
  {
    py::gil_scoped_release release;
    prefilterXSobel(in, cap, f, t, b);
  }
  return py::make_tuple(filtered, texture);
}

py::tuple match(py::handle left, py::handle right, py::handle texture, const StereoParams& params,
                const std::string& backend) {
  const ConstImageView l = inputView(left, {PixelType::U8C1}, "left");
  const ConstImageView r = inputView(right, {PixelType::U8C1}, "right");
  const ConstImageView t =
      texture.is_none() ? ConstImageView{} : inputView(texture, {PixelType::U8C1}, "texture");
  const Backend& b = backendNamed(backend);
  py::array disparity = newImage(l.width, l.height, PixelType::S16C1);
  py::array winner = newImage(l.width, l.height, PixelType::S16C1);
  const ImageView d = outputView(disparity, PixelType::S16C1, "disparity");
  const ImageView w = outputView(winner, PixelType::S16C1, "winner_right");
  {
    py::gil_scoped_release release;
    matchBlocks(l, r, t, params, d, w, b);
  }
  return py::make_tuple(disparity, winner);
}

void lrCheck(py::handle disparity, py::handle winner, const StereoParams& params,
             const std::string& backend) {
  const ImageView d = outputView(disparity, PixelType::S16C1, "disparity");
  const ConstImageView w = inputView(winner, {PixelType::S16C1}, "winner_right");
  const Backend& b = backendNamed(backend);
  py::gil_scoped_release release;
  leftRightCheck(d, w, params, b);
}

void speckles(py::handle disparity, const StereoParams& params, const std::string& backend) {
  const ImageView d = outputView(disparity, PixelType::S16C1, "disparity");
  const Backend& b = backendNamed(backend);
  py::gil_scoped_release release;
  filterSpeckles(d, params, b);
}

py::array median(py::handle src, const MedianParams& params, int invalid,
                 const std::string& backend) {
  const ConstImageView in = inputView(src, {PixelType::S16C1}, "src");
  const Backend& b = backendNamed(backend);
  py::array out = newImage(in.width, in.height, PixelType::S16C1);
  const ImageView o = outputView(out, PixelType::S16C1, "dst");
  {
    py::gil_scoped_release release;
    medianFilter(in, o, params, static_cast<std::int16_t>(invalid), b);
  }
  return out;
}

py::tuple mask(py::handle disparity, py::handle thresholds, int invalid, py::handle image,
               const std::string& backend) {
  const ConstImageView d = inputView(disparity, {PixelType::S16C1}, "disparity");
  const auto table = int16Span(thresholds, "thresholds");
  const Backend& b = backendNamed(backend);
  py::array maskOut = newImage(d.width, d.height, PixelType::U8C1);
  const ImageView mv = outputView(maskOut, PixelType::U8C1, "mask");
  ConstImageView iv;
  ImageView sv;
  py::object segmented = py::none();
  if (!image.is_none()) {
    iv = inputView(image, {PixelType::U8C1, PixelType::U8C3}, "image");
    py::array s = newImage(iv.width, iv.height, iv.type);
    sv = outputView(s, iv.type, "segmented");
    segmented = s;
  }
  {
    py::gil_scoped_release release;
    horopterMask(d, table, static_cast<std::int16_t>(invalid), mv, iv, sv, b);
  }
  return py::make_tuple(maskOut, segmented);
}

}  // namespace

void bindKernels(py::module_& m) {
  m.def("prefilter_xsobel", &prefilter, py::arg("src"), py::arg("cap") = 31,
        py::arg("backend") = "scalar",
        "(filtered, texture) of a uint8 (H, W) image: clamp(sobel, -cap, cap) + cap, and its "
        "absolute value");
  m.def("match_blocks", &match, py::arg("left"), py::arg("right"), py::arg("texture") = py::none(),
        py::arg("params") = StereoParams{}, py::arg("backend") = "scalar",
        "(disparity, winner_right): SAD matching with winner-take-all, texture and uniqueness "
        "checks and sub-pixel refinement; disparity int16 in 1/16 px, winner_right in whole px");
  m.def("left_right_check", &lrCheck, py::arg("disparity"), py::arg("winner_right"),
        py::arg("params") = StereoParams{}, py::arg("backend") = "scalar",
        "Invalidates, in place, disparities that disagree with the right view's winner by more "
        "than params.disp12MaxDiff");
  m.def("filter_speckles", &speckles, py::arg("disparity"), py::arg("params") = StereoParams{},
        py::arg("backend") = "scalar",
        "Invalidates, in place, blobs of at most params.speckleWindowSize pixels");
  m.def("median_filter", &median, py::arg("src"), py::arg("median") = MedianParams{},
        py::arg("invalid") = -16, py::arg("backend") = "scalar",
        "Invalid-aware median that fills holes; a new int16 array");
  m.def("horopter_mask", &mask, py::arg("disparity"), py::arg("thresholds"),
        py::arg("invalid") = -16, py::arg("image") = py::none(), py::arg("backend") = "scalar",
        "(mask, segmented): 255 where the disparity is valid and >= thresholds[column]; "
        "segmented is image zeroed outside (None without an image)");
}

}  // namespace horopter::python
