// Backends, devices, and image files (OpenCV's codecs, so that a script
// needs nothing besides numpy).
#include <pybind11/stl.h>

#include <opencv2/imgcodecs.hpp>

#include "arrays.hpp"
#include "bindings.hpp"
#include "horopter/core/error.hpp"
#include "horopter/kernels/backend.hpp"
#include "horopter/kernels/devices.hpp"

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
    image = cv::imread(path, grey ? cv::IMREAD_GRAYSCALE : cv::IMREAD_UNCHANGED);
  }
  if (image.empty())
    throw Error("could not read the image '" + path + "': check the path and the format");
  return shareMat(image);
}

void imwrite(const std::string& path, py::handle array) {
  cv::Mat mat;
  const py::array a =
      py::isinstance<py::array>(array) ? py::reinterpret_borrow<py::array>(array) : py::array();
  if (a && a.dtype().is(py::dtype::of<std::uint16_t>()) && a.ndim() == 2 && a.strides(1) == 2)
    mat = cv::Mat(static_cast<int>(a.shape(0)), static_cast<int>(a.shape(1)), CV_16UC1,
                  const_cast<void*>(a.data()), static_cast<std::size_t>(a.strides(0)));
  else
    mat = matOver(inputView(array, {PixelType::U8C1, PixelType::U8C3, PixelType::S16C1}, "image"));
  bool ok = false;
  try {
    ok = cv::imwrite(path, mat);
  } catch (const cv::Exception& e) {
    throw Error("could not write '" + path + "': " + e.what());
  }
  if (!ok) throw Error("could not write '" + path + "': check the folder and the extension");
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
        "Writes uint8 (H, W) or (H, W, 3), int16 or uint16 (H, W) to an image file");
}

}  // namespace horopter::python
