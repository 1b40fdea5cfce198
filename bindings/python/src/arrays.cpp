#include "arrays.hpp"

#include <algorithm>

#include "horopter/vision/opencv.hpp"

namespace horopter::python {

namespace {

std::string shapeText(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i)
    s += (i ? ", " : "") + std::to_string(a.shape(i));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

std::string allowedText(std::initializer_list<PixelType> allowed) {
  std::string s;
  for (PixelType t : allowed) {
    if (!s.empty()) s += " or ";
    s += t == PixelType::U8C1   ? "uint8 (H, W)"
         : t == PixelType::U8C3 ? "uint8 (H, W, 3)"
                                : "int16 (H, W)";
  }
  return s;
}

py::array asArray(py::handle obj, const std::string& what) {
  if (!py::isinstance<py::array>(obj))
    throw py::type_error(what + " must be a numpy array, got " +
                         std::string(py::str(py::type::of(obj).attr("__name__"))));
  return py::reinterpret_borrow<py::array>(obj);
}

// The pixel type the array's dtype and shape describe; TypeError for a dtype
// none of `allowed` has, ValueError for a shape none has.
PixelType pixelTypeOf(const py::array& a, std::initializer_list<PixelType> allowed,
                      const std::string& what) {
  const bool u8 = a.dtype().is(py::dtype::of<std::uint8_t>());
  const bool s16 = a.dtype().is(py::dtype::of<std::int16_t>());
  const bool wantsU8 = std::any_of(allowed.begin(), allowed.end(),
                                   [](PixelType t) { return t != PixelType::S16C1; });
  const bool wantsS16 = std::any_of(allowed.begin(), allowed.end(),
                                    [](PixelType t) { return t == PixelType::S16C1; });
  if (!((u8 && wantsU8) || (s16 && wantsS16)))
    throw py::type_error(what + " has dtype " + std::string(py::str(a.dtype())) + ", expected " +
                         allowedText(allowed) + ": convert it with .astype(...)");
  PixelType type = PixelType::U8C1;
  bool shapeOk = false;
  if (s16) {
    type = PixelType::S16C1;
    shapeOk = a.ndim() == 2;
  } else if (a.ndim() == 2) {
    type = PixelType::U8C1;
    shapeOk = true;
  } else if (a.ndim() == 3 && a.shape(2) == 3) {
    type = PixelType::U8C3;
    shapeOk = true;
  }
  if (!shapeOk || std::find(allowed.begin(), allowed.end(), type) == allowed.end())
    throw py::value_error(what + " has shape " + shapeText(a) + ", expected " +
                          allowedText(allowed));
  return type;
}

// The row stride in bytes, after checking that a view over the memory is
// possible without a copy.
std::ptrdiff_t rowStride(const py::array& a, PixelType type, const std::string& what) {
  const auto item = static_cast<py::ssize_t>(a.itemsize());
  const py::ssize_t pixel = static_cast<py::ssize_t>(pixelBytes(type));
  const bool columnsContiguous = a.strides(1) == pixel && (a.ndim() == 2 || a.strides(2) == item);
  if (!columnsContiguous)
    throw py::value_error(what + " has strides (" + std::to_string(a.strides(0)) + ", " +
                          std::to_string(a.strides(1)) +
                          (a.ndim() == 3 ? ", " + std::to_string(a.strides(2)) : std::string()) +
                          "): the pixels of a row must be contiguous, and a view over this "
                          "memory would need a copy; pass np.ascontiguousarray(a) to copy it");
  if (a.shape(0) > 1 && a.strides(0) < a.shape(1) * pixel)
    throw py::value_error(what + " has a row stride of " + std::to_string(a.strides(0)) +
                          " bytes (reversed or overlapping rows): a view over this memory would "
                          "need a copy; pass np.ascontiguousarray(a) to copy it");
  if (type == PixelType::S16C1 &&
      (reinterpret_cast<std::uintptr_t>(a.data()) % 2 != 0 || a.strides(0) % 2 != 0))
    throw py::value_error(what +
                          " is an int16 array not aligned to 2 bytes: a view would need a "
                          "copy; pass np.ascontiguousarray(a) to copy it");
  return a.shape(0) > 1 ? a.strides(0) : a.shape(1) * pixel;
}

void checkSize(const py::array& a, const std::string& what) {
  if (a.shape(0) > (1 << 30) || a.shape(1) > (1 << 30))
    throw py::value_error(what + " is too large: " + shapeText(a));
}

}  // namespace

ConstImageView inputView(py::handle obj, std::initializer_list<PixelType> allowed,
                         const std::string& what) {
  const py::array a = asArray(obj, what);
  const PixelType type = pixelTypeOf(a, allowed, what);
  checkSize(a, what);
  const std::ptrdiff_t stride = rowStride(a, type, what);
  return {a.data(), static_cast<int>(a.shape(1)), static_cast<int>(a.shape(0)), stride, type};
}

ImageView outputView(py::handle obj, PixelType type, const std::string& what) {
  py::array a = asArray(obj, what);
  const PixelType actual = pixelTypeOf(a, {type}, what);
  if (!a.writeable())
    throw py::value_error(what + " is read-only: pass a writable array (a.copy())");
  checkSize(a, what);
  const std::ptrdiff_t stride = rowStride(a, actual, what);
  return {a.mutable_data(), static_cast<int>(a.shape(1)), static_cast<int>(a.shape(0)), stride,
          actual};
}

std::span<const std::int16_t> int16Span(py::handle obj, const std::string& what) {
  const py::array a = asArray(obj, what);
  if (!a.dtype().is(py::dtype::of<std::int16_t>()))
    throw py::type_error(what + " has dtype " + std::string(py::str(a.dtype())) +
                         ", expected int16: convert it with .astype(np.int16)");
  if (a.ndim() != 1)
    throw py::value_error(what + " has shape " + shapeText(a) + ", expected one dimension");
  if (a.shape(0) > 1 && a.strides(0) != 2)
    throw py::value_error(what +
                          " is not contiguous: a view would need a copy; pass "
                          "np.ascontiguousarray(a) to copy it");
  return {static_cast<const std::int16_t*>(a.data()), static_cast<std::size_t>(a.shape(0))};
}

py::array newImage(int width, int height, PixelType type) {
  switch (type) {
    case PixelType::U8C1:
      return py::array_t<std::uint8_t>({height, width});
    case PixelType::U8C3:
      return py::array_t<std::uint8_t>({height, width, 3});
    case PixelType::S16C1:
      return py::array_t<std::int16_t>({height, width});
  }
  throw py::value_error("unknown pixel type");
}

py::array copyOf(const Image& image) {
  if (image.empty()) return py::none();
  py::array out = newImage(image.width(), image.height(), image.type());
  const std::size_t rowBytes = static_cast<std::size_t>(image.width()) * pixelBytes(image.type());
  auto* dst = static_cast<std::uint8_t*>(out.mutable_data());
  for (int y = 0; y < image.height(); ++y)
    std::copy_n(image.row<std::uint8_t>(y), rowBytes, dst + static_cast<std::size_t>(y) * rowBytes);
  return out;
}

py::array shareMat(const cv::Mat& mat) {
  if (mat.empty()) return py::none();
  if (mat.dims != 2) throw py::value_error("only two-dimensional images are supported");
  auto* keep = new cv::Mat(mat);  // shares the pixels: numpy takes any row stride
  py::capsule owner(keep, [](void* p) { delete static_cast<cv::Mat*>(p); });
  py::dtype dtype;
  switch (keep->depth()) {
    case CV_8U:
      dtype = py::dtype::of<std::uint8_t>();
      break;
    case CV_16S:
      dtype = py::dtype::of<std::int16_t>();
      break;
    case CV_16U:
      dtype = py::dtype::of<std::uint16_t>();
      break;
    case CV_32F:
      dtype = py::dtype::of<float>();
      break;
    case CV_64F:
      dtype = py::dtype::of<double>();
      break;
    default:
      throw py::type_error("cv::Mat of type " + cv::typeToString(keep->type()) +
                           " has no numpy counterpart here");
  }
  const auto rows = static_cast<py::ssize_t>(keep->rows),
             cols = static_cast<py::ssize_t>(keep->cols);
  const auto step = static_cast<py::ssize_t>(keep->step[0]);
  const auto elem = static_cast<py::ssize_t>(keep->elemSize());
  const auto elem1 = static_cast<py::ssize_t>(keep->elemSize1());
  if (keep->channels() == 1) return py::array(dtype, {rows, cols}, {step, elem}, keep->data, owner);
  return py::array(dtype, {rows, cols, static_cast<py::ssize_t>(keep->channels())},
                   {step, elem, elem1}, keep->data, owner);
}

cv::Mat matOver(const ConstImageView& view) {
  return matOf(view);
}

}  // namespace horopter::python
