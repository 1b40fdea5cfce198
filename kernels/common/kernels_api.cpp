// Public kernel entry points: validate, then dispatch to the backend's table.
// Backends receive only arguments that passed these checks.
#include <algorithm>
#include <cstdint>
#include <string>

#include "common/kernel_table.hpp"
#include "horopter/core/error.hpp"
#include "horopter/kernels/kernels.hpp"
#include "sad/sad.hpp"

namespace horopter {

namespace {

std::string size(const ConstImageView& v) {
  return std::to_string(v.width) + "x" + std::to_string(v.height);
}

// True when the byte ranges of the two views overlap.
bool overlaps(const ConstImageView& a, const ConstImageView& b) {
  if (a.empty() || b.empty()) return false;
  const auto* a0 = static_cast<const std::uint8_t*>(a.data);
  const auto* b0 = static_cast<const std::uint8_t*>(b.data);
  const auto* a1 = a0 + (a.height - 1) * a.strideBytes + a.width * pixelBytes(a.type);
  const auto* b1 = b0 + (b.height - 1) * b.strideBytes + b.width * pixelBytes(b.type);
  return a0 < b1 && b0 < a1;
}

// Resolves RowRange::all() and checks an explicit range against the height.
RowRange resolveRows(RowRange rows, int height) {
  if (rows.isAll()) return {0, height};
  if (rows.begin < 0 || rows.begin > rows.end || rows.end > height)
    throw Error("row range [" + std::to_string(rows.begin) + ", " + std::to_string(rows.end) +
                ") is not within the image's " + std::to_string(height) +
                " rows: use 0 <= begin <= end <= height");
  return rows;
}

// A backend without a table (one that is not available) has no kernel:
// requireKernel then names the kernel asked for.
const KernelTable& tableOf(const Backend& backend) {
  static const KernelTable none{};
  return backend.kernels ? *backend.kernels : none;
}

void requireKernel(const void* fn, const Backend& backend, const char* kernel) {
  if (fn == nullptr) throw Error("backend '" + backend.name + "' has no " + kernel + " kernel");
}

void checkPrefilterArgs(const ConstImageView& src, int cap, const ImageView& filtered,
                        const ImageView& texture, const char* kernel) {
  checkView(src, PixelType::U8C1, "prefilter input");
  if (cap < 1 || cap > 63)
    throw Error("preFilterCap must be within 1..63, got " + std::to_string(cap));
  if (filtered.empty() && texture.empty())
    throw Error(std::string(kernel) + ": give at least one output (filtered or texture)");
  if (!filtered.empty()) {
    checkView(filtered, PixelType::U8C1, "prefilter output");
    checkSameSize(src, "prefilter input", filtered, "prefilter output");
  }
  if (!texture.empty()) {
    checkView(texture, PixelType::U8C1, "texture output");
    checkSameSize(src, "prefilter input", texture, "texture output");
  }
  if (overlaps(src, filtered) || overlaps(src, texture) || overlaps(filtered, texture))
    throw Error(std::string(kernel) + ": input and outputs must not overlap");
}

}  // namespace

void prefilterXSobel(const ConstImageView& src, int cap, const ImageView& filtered,
                     const ImageView& texture, const Backend& backend, RowRange rows) {
  checkPrefilterArgs(src, cap, filtered, texture, "prefilterXSobel");
  requireKernel(reinterpret_cast<const void*>(tableOf(backend).prefilterXSobel), backend,
                "prefilter");
  tableOf(backend).prefilterXSobel(src, cap, filtered, texture, resolveRows(rows, src.height));
}

void prefilterNormalized(const ConstImageView& src, int cap, int size, const ImageView& filtered,
                         const ImageView& texture, const Backend& backend, RowRange rows) {
  checkPrefilterArgs(src, cap, filtered, texture, "prefilterNormalized");
  if (size < 5 || size > 255 || size % 2 == 0)
    throw Error("preFilterSize must be odd, 5..255, got " + std::to_string(size));
  requireKernel(reinterpret_cast<const void*>(tableOf(backend).prefilterNormalized), backend,
                "normalized-response prefilter");
  tableOf(backend).prefilterNormalized(src, cap, size, filtered, texture,
                                       resolveRows(rows, src.height));
}

void prefilter(const ConstImageView& src, const StereoParams& params, const ImageView& filtered,
               const ImageView& texture, const Backend& backend, RowRange rows) {
  validate(params);
  switch (params.preFilterType) {
    case PreFilterType::XSobel:
      prefilterXSobel(src, params.preFilterCap, filtered, texture, backend, rows);
      return;
    case PreFilterType::NormalizedResponse:
      prefilterNormalized(src, params.preFilterCap, params.preFilterSize, filtered, texture,
                          backend, rows);
      return;
    case PreFilterType::None:
      if (!filtered.empty())
        throw Error(
            "prefilter: preFilterType is none, which filters nothing: pass an empty "
            "filtered output (the texture output gets the x-Sobel texture)");
      prefilterXSobel(src, params.preFilterCap, {}, texture, backend, rows);
      return;
  }
}

void matchBlocks(const ConstImageView& left, const ConstImageView& right,
                 const ConstImageView& texture, const StereoParams& params,
                 const ImageView& disparity, const ImageView& winnerRight, const Backend& backend,
                 RowRange rows) {
  matchBlocks(left, right, texture, params, BelowRangeGuard{}, disparity, winnerRight, backend,
              rows);
}

void matchBlocks(const ConstImageView& left, const ConstImageView& right,
                 const ConstImageView& texture, const StereoParams& params,
                 const BelowRangeGuard& guard, const ImageView& disparity,
                 const ImageView& winnerRight, const Backend& backend, RowRange rows) {
  validate(params);
  if (guard.step < 0 || guard.step > kMaxGuardStep)
    throw Error("guard step " + std::to_string(guard.step) + " px is not within 0.." +
                std::to_string(kMaxGuardStep) + " (0: no guard)");
  if (guard.step > 0 &&
      (guard.lowest > params.minDisparity || guard.lowest < params.minDisparity - 1024))
    throw Error("guard's lowest disparity " + std::to_string(guard.lowest) +
                " px is not within [minDisparity - 1024, minDisparity] = [" +
                std::to_string(params.minDisparity - 1024) + ", " +
                std::to_string(params.minDisparity) + "]");
  checkView(left, PixelType::U8C1, "left image");
  checkView(right, PixelType::U8C1, "right image");
  checkSameSize(left, "left image", right, "right image");
  checkView(disparity, PixelType::S16C1, "disparity output");
  checkSameSize(left, "left image", disparity, "disparity output");
  checkView(winnerRight, PixelType::S16C1, "right-winner output");
  checkSameSize(left, "left image", winnerRight, "right-winner output");
  if (params.textureThreshold > 0) {
    if (texture.empty())
      throw Error("textureThreshold is " + std::to_string(params.textureThreshold) +
                  " but no texture image was given: pass prefilterXSobel's texture output, or "
                  "set textureThreshold to 0");
    checkView(texture, PixelType::U8C1, "texture image");
    checkSameSize(left, "left image", texture, "texture image");
  }
  if (left.width < params.blockSize || left.height < params.blockSize)
    throw Error("image " + size(left) + " is smaller than the " + std::to_string(params.blockSize) +
                "x" + std::to_string(params.blockSize) +
                " block: use a smaller blockSize or a larger image");
  if (matchRegion(left.width, left.height, params).empty()) {
    const int maxD = params.minDisparity + params.numDisparities - 1;
    const int needed = params.blockSize + std::max(maxD, 0) - std::min(params.minDisparity, 0);
    throw Error("image width " + std::to_string(left.width) +
                " leaves no column where every disparity fits: matching needs width >= "
                "blockSize + max(maxDisparity, 0) - min(minDisparity, 0) = " +
                std::to_string(needed) + "; reduce numDisparities or blockSize");
  }
  for (const ConstImageView* in : {&left, &right, &texture}) {
    if (overlaps(*in, disparity) || overlaps(*in, winnerRight))
      throw Error("matchBlocks: outputs must not overlap the inputs");
  }
  if (overlaps(disparity, winnerRight))
    throw Error("matchBlocks: the disparity and right-winner outputs must not overlap");
  requireKernel(reinterpret_cast<const void*>(tableOf(backend).matchBlocks), backend, "matching");
  tableOf(backend).matchBlocks(left, right, texture, params, guard, disparity, winnerRight,
                               resolveRows(rows, left.height));
}

void leftRightCheck(const ImageView& disparity, const ConstImageView& winnerRight,
                    const StereoParams& params, const Backend& backend, RowRange rows) {
  validate(params);
  checkView(disparity, PixelType::S16C1, "disparity");
  checkView(winnerRight, PixelType::S16C1, "right-winner map");
  checkSameSize(disparity, "disparity", winnerRight, "right-winner map");
  if (overlaps(disparity, winnerRight))
    throw Error("leftRightCheck: the disparity and the right-winner map must not overlap");
  requireKernel(reinterpret_cast<const void*>(tableOf(backend).leftRightCheck), backend,
                "left-right check");
  tableOf(backend).leftRightCheck(disparity, winnerRight, params,
                                  resolveRows(rows, disparity.height));
}

void filterSpeckles(const ImageView& disparity, const StereoParams& params,
                    const Backend& backend) {
  validate(params);
  checkView(disparity, PixelType::S16C1, "disparity");
  requireKernel(reinterpret_cast<const void*>(tableOf(backend).filterSpeckles), backend, "speckle");
  tableOf(backend).filterSpeckles(disparity, params);
}

void medianFilter(const ConstImageView& src, const ImageView& dst, const MedianParams& median,
                  std::int16_t invalid, const Backend& backend, RowRange rows) {
  validate(median);
  if (median.kernelSize == 0)
    throw Error("medianFilter: kernelSize 0 means off; skip the call, or use 3 or 5");
  checkView(src, PixelType::S16C1, "median input");
  checkView(dst, PixelType::S16C1, "median output");
  checkSameSize(src, "median input", dst, "median output");
  if (overlaps(src, dst))
    throw Error("medianFilter: input and output must not overlap (it cannot run in place)");
  requireKernel(reinterpret_cast<const void*>(tableOf(backend).medianFilter), backend, "median");
  tableOf(backend).medianFilter(src, dst, median.kernelSize, effectiveMinValid(median), invalid,
                                resolveRows(rows, src.height));
}

void horopterMask(const ConstImageView& disparity, std::span<const std::int16_t> thresholds,
                  std::int16_t invalid, const ImageView& mask, const ConstImageView& image,
                  const ImageView& segmented, const Backend& backend, RowRange rows) {
  checkView(disparity, PixelType::S16C1, "disparity");
  checkView(mask, PixelType::U8C1, "mask output");
  checkSameSize(disparity, "disparity", mask, "mask output");
  if (thresholds.data() == nullptr ||
      thresholds.size() != static_cast<std::size_t>(disparity.width))
    throw Error("horopter threshold table has " + std::to_string(thresholds.size()) +
                " entries but the disparity is " + std::to_string(disparity.width) +
                " columns wide: give one threshold per column");
  if (!segmented.empty()) {
    checkViewOneOf(image, {PixelType::U8C1, PixelType::U8C3}, "image to segment");
    checkSameSize(disparity, "disparity", image, "image to segment");
    checkView(segmented, image.type, "segmented output");
    checkSameSize(disparity, "disparity", segmented, "segmented output");
    if (overlaps(image, segmented) || overlaps(mask, segmented))
      throw Error("horopterMask: the segmented output must not overlap the image or the mask");
  }
  if (overlaps(disparity, mask))
    throw Error("horopterMask: the mask must not overlap the disparity");
  requireKernel(reinterpret_cast<const void*>(tableOf(backend).horopterMask), backend,
                "horopter mask");
  tableOf(backend).horopterMask(disparity, thresholds, invalid, mask, image, segmented,
                                resolveRows(rows, disparity.height));
}

}  // namespace horopter
