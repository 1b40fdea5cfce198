#include "horopter/core/image.hpp"

#include <cstdlib>
#include <cstring>
#include <limits>

namespace horopter {

std::size_t pixelBytes(PixelType type) {
  switch (type) {
    case PixelType::U8C1:
      return 1;
    case PixelType::U8C3:
      return 3;
    case PixelType::S16C1:
      return 2;
  }
  return 1;
}

const char* pixelTypeName(PixelType type) {
  switch (type) {
    case PixelType::U8C1:
      return "U8C1";
    case PixelType::U8C3:
      return "U8C3";
    case PixelType::S16C1:
      return "S16C1";
  }
  return "?";
}

ConstImageView makeView(const void* data, int width, int height, PixelType type) {
  return {data, width, height, static_cast<std::ptrdiff_t>(width * pixelBytes(type)), type};
}

ImageView makeView(void* data, int width, int height, PixelType type) {
  return {data, width, height, static_cast<std::ptrdiff_t>(width * pixelBytes(type)), type};
}

namespace {

void checkGeometry(const ConstImageView& view, const char* what) {
  const std::string name(what);
  if (view.data == nullptr) throw Error(name + " is empty (null data pointer): pass an image");
  if (view.width <= 0 || view.height <= 0)
    throw Error(name + " is empty (" + std::to_string(view.width) + "x" +
                std::to_string(view.height) + "): pass an image of positive size");
  const auto rowBytes = static_cast<std::ptrdiff_t>(view.width * pixelBytes(view.type));
  if (view.strideBytes < rowBytes)
    throw Error(name + " has a row stride of " + std::to_string(view.strideBytes) +
                " bytes, smaller than its row of " + std::to_string(rowBytes) +
                " bytes: the stride must be at least width * bytes per pixel");
}

}  // namespace

void checkView(const ConstImageView& view, PixelType expected, const char* what) {
  checkGeometry(view, what);
  if (view.type != expected)
    throw Error(std::string(what) + " has pixel type " + pixelTypeName(view.type) + ", expected " +
                pixelTypeName(expected));
}

void checkViewOneOf(const ConstImageView& view, std::initializer_list<PixelType> allowed,
                    const char* what) {
  checkGeometry(view, what);
  std::string names;
  for (PixelType t : allowed) {
    if (view.type == t) return;
    names += names.empty() ? "" : " or ";
    names += pixelTypeName(t);
  }
  throw Error(std::string(what) + " has pixel type " + pixelTypeName(view.type) + ", expected " +
              names);
}

void checkSameSize(const ConstImageView& a, const char* whatA, const ConstImageView& b,
                   const char* whatB) {
  if (a.width != b.width || a.height != b.height)
    throw Error(std::string(whatB) + " is " + std::to_string(b.width) + "x" +
                std::to_string(b.height) + " but " + whatA + " is " + std::to_string(a.width) +
                "x" + std::to_string(a.height) + ": they must have the same size");
}

Image::Image(int width, int height, PixelType type) : width_(width), height_(height), type_(type) {
  if (width < 0 || height < 0)
    throw Error("Image size must not be negative, got " + std::to_string(width) + "x" +
                std::to_string(height));
  const std::size_t row = static_cast<std::size_t>(width) * pixelBytes(type);
  stride_ = static_cast<std::ptrdiff_t>((row + kAlignment - 1) / kAlignment * kAlignment);
  const std::size_t bytes = static_cast<std::size_t>(stride_) * static_cast<std::size_t>(height);
  if (bytes == 0) return;
  if (height > 0 && static_cast<std::size_t>(stride_) >
                        std::numeric_limits<std::size_t>::max() / static_cast<std::size_t>(height))
    throw Error("Image of " + std::to_string(width) + "x" + std::to_string(height) +
                " is too large to allocate");
  void* p = std::aligned_alloc(kAlignment, bytes);
  if (p == nullptr)
    throw Error("Out of memory allocating a " + std::to_string(width) + "x" +
                std::to_string(height) + " image");
  std::memset(p, 0, bytes);
  data_.reset(static_cast<std::uint8_t*>(p));
}

void Image::fillBytes(std::uint8_t value) {
  if (data_) std::memset(data_.get(), value, static_cast<std::size_t>(stride_) * height_);
}

void Image::FreeAligned::operator()(std::uint8_t* p) const {
  std::free(p);
}

}  // namespace horopter
