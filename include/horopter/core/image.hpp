// Image views over caller memory, and an owned, aligned, padded image.
//
// A view never owns or copies: it is a pointer, a size, a row stride in bytes
// and a pixel type. Kernels take views, so camera buffers, numpy arrays and
// cv::Mat share memory with Horopter without hidden copies.
#pragma once

#include "horopter/core/export.hpp"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "horopter/core/error.hpp"

namespace horopter {

enum class PixelType {
  U8C1,   // 8-bit grey
  U8C3,   // 8-bit, 3 interleaved channels (BGR as OpenCV)
  S16C1,  // signed 16-bit (disparity in 1/16 px)
};

// Bytes of one pixel of this type.
HOROPTER_API std::size_t pixelBytes(PixelType type);
// "U8C1", "U8C3", "S16C1".
HOROPTER_API const char* pixelTypeName(PixelType type);

// A read-only view. Row y starts at data + y * strideBytes.
struct HOROPTER_API ConstImageView {
  const void* data = nullptr;
  int width = 0;
  int height = 0;
  std::ptrdiff_t strideBytes = 0;
  PixelType type = PixelType::U8C1;

  bool empty() const { return data == nullptr || width <= 0 || height <= 0; }

  template <typename T>
  const T* row(int y) const {
    return reinterpret_cast<const T*>(static_cast<const std::uint8_t*>(data) + y * strideBytes);
  }
};

// A writable view.
struct HOROPTER_API ImageView {
  void* data = nullptr;
  int width = 0;
  int height = 0;
  std::ptrdiff_t strideBytes = 0;
  PixelType type = PixelType::U8C1;

  bool empty() const { return data == nullptr || width <= 0 || height <= 0; }

  template <typename T>
  T* row(int y) const {
    return reinterpret_cast<T*>(static_cast<std::uint8_t*>(data) + y * strideBytes);
  }

  operator ConstImageView() const { return {data, width, height, strideBytes, type}; }
};

// Builds a view with the tightest stride for its width (width * pixelBytes).
HOROPTER_API ConstImageView makeView(const void* data, int width, int height, PixelType type);
HOROPTER_API ImageView makeView(void* data, int width, int height, PixelType type);

// Throws horopter::Error unless the view is usable as `what` ("left image"):
// non-null, positive size, the expected pixel type, stride >= width * bytes.
HOROPTER_API void checkView(const ConstImageView& view, PixelType expected, const char* what);
// The same for a view of any of the listed pixel types.
HOROPTER_API void checkViewOneOf(const ConstImageView& view,
                                 std::initializer_list<PixelType> allowed, const char* what);
// Throws unless `b` has the size of `a`.
HOROPTER_API void checkSameSize(const ConstImageView& a, const char* whatA, const ConstImageView& b,
                                const char* whatB);

// An owned image: 64-byte aligned rows, each padded to a multiple of 64 bytes,
// so that vector code can read whole vectors at the end of a row.
class HOROPTER_API Image {
 public:
  static constexpr std::size_t kAlignment = 64;

  Image() = default;
  Image(int width, int height, PixelType type);

  int width() const { return width_; }
  int height() const { return height_; }
  PixelType type() const { return type_; }
  std::ptrdiff_t strideBytes() const { return stride_; }
  bool empty() const { return width_ == 0 || height_ == 0; }

  ImageView view() { return {data_.get(), width_, height_, stride_, type_}; }
  ConstImageView view() const { return {data_.get(), width_, height_, stride_, type_}; }

  template <typename T>
  T* row(int y) {
    return view().row<T>(y);
  }
  template <typename T>
  const T* row(int y) const {
    return view().row<T>(y);
  }

  // Sets every byte of every row (padding included) to `value`.
  void fillBytes(std::uint8_t value);

 private:
  struct FreeAligned {
    void operator()(std::uint8_t* p) const;
  };
  std::unique_ptr<std::uint8_t, FreeAligned> data_;
  int width_ = 0;
  int height_ = 0;
  std::ptrdiff_t stride_ = 0;
  PixelType type_ = PixelType::U8C1;
};

}  // namespace horopter
