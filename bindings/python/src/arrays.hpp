// numpy arrays <-> Horopter image views, without copies.
//
// Inputs: an array whose rows are each contiguous (C-contiguous, or a strided
// view such as a[10:50, 20:80] of one) becomes a view over its memory. An
// array that would need a copy (columns not contiguous, rows backwards or
// overlapping, misaligned int16) is refused with ValueError saying so; a
// wrong dtype is a TypeError. Outputs are new numpy arrays the kernels write
// into, or cv::Mat buffers handed to numpy with their reference count.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstdint>
#include <initializer_list>
#include <opencv2/core.hpp>
#include <span>
#include <string>

#include "horopter/core/image.hpp"

namespace horopter::python {

namespace py = pybind11;

// A read-only view over `obj`'s memory. `allowed` lists the pixel types the
// caller takes: uint8 (H, W) is U8C1, uint8 (H, W, 3) is U8C3, int16 (H, W)
// is S16C1.
ConstImageView inputView(py::handle obj, std::initializer_list<PixelType> allowed,
                         const std::string& what);
// A writable view over `obj`'s memory (in-place kernels, out= arrays).
ImageView outputView(py::handle obj, PixelType type, const std::string& what);

// A one-dimensional, contiguous int16 array (a threshold table) as a span.
std::span<const std::int16_t> int16Span(py::handle obj, const std::string& what);

// A new, uninitialised C-contiguous array for an image of this size and type.
py::array newImage(int width, int height, PixelType type);
// A copy of an owned image into a new array (the front end reuses its buffers).
py::array copyOf(const Image& image);
// The Mat's pixels as an array sharing its memory (the Mat's reference count
// keeps them alive).
py::array shareMat(const cv::Mat& mat);
// A cv::Mat header over a view's memory (no copy), for OpenCV calls.
cv::Mat matOver(const ConstImageView& view);

}  // namespace horopter::python
