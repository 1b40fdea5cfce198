// Backends, devices, and image files (OpenCV's codecs, so that a script
// needs nothing besides numpy).
#include <pybind11/stl.h>

#include <opencv2/imgcodecs.hpp>

#include "arrays.hpp"
#include "bindings.hpp"
#include "horopter/core/error.hpp"
#include "horopter/kernels/backend.hpp"
#include "horopter/kernels/devices.hpp"
#include "io/disparity_images.hpp"
#include "io/image_files.hpp"

namespace horopter::python {

namespace {

py::dict backendDict(const Backend& b) {
  py::dict d;
  d["name"] = b.name;
  d["description"] = b.description;
  d["available"] = b.available;
  d["unavailable_reason"] = b.unavailableReason;
  return d;
}

py::dict devices() {
  const CpuInfo cpu = probeCpu();
  const OpenClReport cl = probeOpenCl();
  py::dict c;
  c["model"] = cpu.model;
  c["hardware_threads"] = cpu.hardwareThreads;
  c["features"] = cpu.features;
  py::list list;
  for (const OpenClDevice& dev : cl.devices) {
    py::dict d;
    d["platform"] = dev.platform;
    d["device"] = dev.device;
    d["platform_name"] = dev.platformName;
    d["device_name"] = dev.deviceName;
    d["type"] = dev.type;
    d["version"] = dev.version;
    d["compute_units"] = dev.computeUnits;
    d["global_mem_bytes"] = dev.globalMemBytes;
    list.append(d);
  }
  py::dict o;
  o["built"] = cl.built;
  o["error"] = cl.error;
  o["devices"] = list;
  py::dict out;
  out["cpu"] = c;
  out["opencl"] = o;
  py::list backends;
  for (const Backend* b : registeredBackends())
    backends.append(backendDict(*b));
  out["backends"] = backends;
  return out;
}

py::array imread(const std::string& path, bool grey) {
  cv::Mat image;
  {
    py::gil_scoped_release release;
    image = readImage(path, grey ? cv::IMREAD_GRAYSCALE : cv::IMREAD_UNCHANGED);
  }
  if (image.empty())
    throw Error("could not read the image '" + path + "': check the path and the format");
  return shareMat(image);
}

void imwrite(const std::string& path, py::handle array) {
  cv::Mat mat;
  const py::array a =
      py::isinstance<py::array>(array) ? py::reinterpret_borrow<py::array>(array) : py::array();
  // OpenCV's PNG encoder would cut int16 to 8 bits: refuse it, and name the
  // writers that keep a signed disparity map.
  if (a && a.dtype().is(py::dtype::of<std::int16_t>()))
    throw Error("cannot write '" + path +
                "': imwrite does not take int16 (an image format would lose the sign); for "
                "a disparity map use write_disparity16 (16-bit PNG, d16 + 32768, 0 = invalid) "
                "or write_pfm (PFM, float px, inf = invalid)");
  if (a && a.dtype().is(py::dtype::of<std::uint16_t>()) && a.ndim() == 2 && a.strides(1) == 2)
    mat = cv::Mat(static_cast<int>(a.shape(0)), static_cast<int>(a.shape(1)), CV_16UC1,
                  const_cast<void*>(a.data()), static_cast<std::size_t>(a.strides(0)));
  else
    mat = matOver(inputView(array, {PixelType::U8C1, PixelType::U8C3}, "image"));
  bool ok = false;
  try {
    ok = cv::imwrite(path, mat);
  } catch (const cv::Exception& e) {
    throw Error("could not write '" + path + "': " + e.what());
  }
  if (!ok) throw Error("could not write '" + path + "': check the folder and the extension");
}

void writeDisparity16(const std::string& path, py::handle disparity, int invalid) {
  const ConstImageView d = inputView(disparity, {PixelType::S16C1}, "disparity");
  writeDisparity16Png(path, d, static_cast<std::int16_t>(invalid));
}

py::array readDisparity16(const std::string& path, int invalid) {
  cv::Mat d;
  {
    py::gil_scoped_release release;
    d = readDisparity16Png(path, static_cast<std::int16_t>(invalid));
  }
  return shareMat(d);
}

void writePfmFile(const std::string& path, py::handle image, py::object invalid) {
  const py::array a =
      py::isinstance<py::array>(image) ? py::reinterpret_borrow<py::array>(image) : py::array();
  if (a && a.dtype().is(py::dtype::of<std::int16_t>())) {
    if (invalid.is_none())
      throw Error(
          "write_pfm of an int16 disparity map (1/16 px) needs invalid= (the "
          "matcher's params.invalidDisparity), written as inf");
    writeDisparityPfm(path, inputView(image, {PixelType::S16C1}, "disparity"),
                      static_cast<std::int16_t>(invalid.cast<int>()));
    return;
  }
  if (!a || a.ndim() != 2 || a.dtype().kind() != 'f')
    throw Error(
        "write_pfm takes a float (H, W) array in px (inf = invalid) or an int16 (H, W) "
        "disparity map in 1/16 px with invalid=");
  const auto f = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(a);
  const cv::Mat mat(static_cast<int>(f.shape(0)), static_cast<int>(f.shape(1)), CV_32FC1,
                    const_cast<float*>(f.data()));
  writePfm(path, mat);
}

py::array readPfmFile(const std::string& path) {
  cv::Mat px;
  {
    py::gil_scoped_release release;
    px = readPfm(path);
  }
  return shareMat(px);
}

}  // namespace

void bindSystem(py::module_& m) {
  m.def(
      "backends",
      [] {
        py::list out;
        for (const Backend* b : registeredBackends())
          out.append(backendDict(*b));
        return out;
      },
      "Every backend of this build, available here or not, best last: list of dicts");
  m.def(
      "find_backend", [](const std::string& name) { return findBackend(name).name; },
      py::arg("name") = "auto",
      "The name of the backend 'auto' (or a name, or a part of an OpenCL device's name) picks");
  m.def("devices", &devices, "CPU features, OpenCL devices and backends: a dict");
  m.def("imread", &imread, py::arg("path"), py::arg("grey") = false,
        "An image file as a numpy array (uint8 BGR (H, W, 3), grey (H, W), or 16-bit)");
  m.def("imwrite", &imwrite, py::arg("path"), py::arg("image"),
        "Writes uint8 (H, W) or (H, W, 3), or uint16 (H, W) to an image file. int16 raises "
        "horopter.Error: write a disparity map with write_disparity16 or write_pfm");
  m.def("write_disparity16", &writeDisparity16, py::arg("path"), py::arg("disparity"),
        py::arg("invalid"),
        "Writes an int16 disparity map (1/16 px) as a 16-bit PNG that keeps negative and "
        "sub-pixel values: each pixel holds d16 + 32768, 0 = invalid (pixels equal to "
        "`invalid`). Decode: px = (value - 32768) / 16 where value != 0. The CLI's "
        "disparity16.png");
  m.def("read_disparity16", &readDisparity16, py::arg("path"), py::arg("invalid"),
        "Reads a write_disparity16 PNG (or the CLI's disparity16.png) back as int16 in 1/16 px, "
        "with `invalid` where the file holds 0");
  m.def("write_pfm", &writePfmFile, py::arg("path"), py::arg("image"),
        py::arg("invalid") = py::none(),
        "Writes Middlebury's PFM (float32 px, grey): a float (H, W) array as is, or an int16 "
        "disparity map in 1/16 px converted to px with inf where it equals `invalid`. The "
        "CLI's disparity.pfm");
  m.def("read_pfm", &readPfmFile, py::arg("path"),
        "Reads a PFM file (either byte order; a colour one's first channel) as float32 (H, W), "
        "top row first; inf and NaN are kept (Middlebury: inf = unknown)");
}

}  // namespace horopter::python
