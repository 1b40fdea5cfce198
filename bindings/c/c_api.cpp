// The C API (include/horopter/horopter.h) over the C++ library. Every entry
// point runs its body inside `guarded`, which turns any exception into a
// status and the thread's last-error message: nothing crosses into C.
#include <cstring>
#include <exception>
#include <new>
#include <string>
#include <type_traits>
#include <vector>

#include "guarded.hpp"
#include "horopter/core/error.hpp"
#include "horopter/horopter.h"
#include "horopter/kernels/backend.hpp"
#include "horopter/vision/calibration.hpp"
#include "horopter/vision/frontend.hpp"
#include "horopter/vision/geometry.hpp"

struct horopter_matcher {
  horopter::StereoFrontend frontend;
};

using namespace horopter::c_api;

namespace {

// The C caller may store any int in the enum field: read its bytes as an
// int (loading an out-of-range value as the C++ enum is undefined behaviour).
horopter::PixelType pixelType(const horopter_pixel_type& field) {
  std::underlying_type_t<horopter_pixel_type> raw;
  static_assert(sizeof raw == sizeof field);
  std::memcpy(&raw, &field, sizeof raw);
  switch (raw) {
    case HOROPTER_U8C1:
      return horopter::PixelType::U8C1;
    case HOROPTER_U8C3:
      return horopter::PixelType::U8C3;
    case HOROPTER_S16C1:
      return horopter::PixelType::S16C1;
    default:
      break;
  }
  throw InvalidArgument("unknown pixel type " + std::to_string(raw) +
                        ": use HOROPTER_U8C1, HOROPTER_U8C3 or HOROPTER_S16C1");
}

horopter_pixel_type pixelType(horopter::PixelType t) {
  switch (t) {
    case horopter::PixelType::U8C1:
      return HOROPTER_U8C1;
    case horopter::PixelType::U8C3:
      return HOROPTER_U8C3;
    case horopter::PixelType::S16C1:
      return HOROPTER_S16C1;
  }
  return HOROPTER_U8C1;
}

horopter::ConstImageView viewOf(const horopter_image& image) {
  return {image.data, image.width, image.height, image.stride_bytes, pixelType(image.type)};
}

horopter_image imageOf(const horopter::Image& image) {
  if (image.empty()) return {nullptr, 0, 0, 0, HOROPTER_U8C1};
  const horopter::ConstImageView v = image.view();
  return {const_cast<void*>(v.data), v.width, v.height, v.strideBytes, pixelType(v.type)};
}

horopter::RectifiedGeometry geometryOf(const horopter_geometry* g) {
  requireNonNull(g, "geometry");
  horopter::RectifiedGeometry out;
  out.focalPx = g->focal_px;
  out.cx = g->cx;
  out.cy = g->cy;
  out.baseline = g->baseline;
  return out;
}

void requireTable(const int16_t* out, int width) {
  requireNonNull(out, "threshold table");
  if (width <= 0)
    throw InvalidArgument("threshold table width must be positive, got " + std::to_string(width));
}

void copyTable(const std::vector<std::int16_t>& table, int16_t* out) {
  std::memcpy(out, table.data(), table.size() * sizeof(std::int16_t));
}

}  // namespace

namespace horopter::c_api {

static_assert(static_cast<int>(PreFilterType::NormalizedResponse) ==
              HOROPTER_PREFILTER_NORMALIZED_RESPONSE);
static_assert(static_cast<int>(PreFilterType::XSobel) == HOROPTER_PREFILTER_XSOBEL);
static_assert(static_cast<int>(PreFilterType::None) == HOROPTER_PREFILTER_NONE);

void paramsOf(const horopter_stereo_params& c, StereoParams& s, MedianParams& m) {
  s.minDisparity = c.min_disparity;
  s.numDisparities = c.num_disparities;
  s.blockSize = c.block_size;
  if (c.pre_filter_type < HOROPTER_PREFILTER_NORMALIZED_RESPONSE ||
      c.pre_filter_type > HOROPTER_PREFILTER_NONE)
    throw InvalidArgument(
        "pre_filter_type must be HOROPTER_PREFILTER_NORMALIZED_RESPONSE (0), "
        "HOROPTER_PREFILTER_XSOBEL (1) or HOROPTER_PREFILTER_NONE (2), got " +
        std::to_string(c.pre_filter_type));
  // The enumerators carry OpenCV's values, as PreFilterType's do.
  s.preFilterType = static_cast<horopter::PreFilterType>(c.pre_filter_type);
  s.preFilterSize = c.pre_filter_size;
  s.preFilterCap = c.pre_filter_cap;
  s.textureThreshold = c.texture_threshold;
  s.uniquenessRatio = c.uniqueness_ratio;
  s.disp12MaxDiff = c.disp12_max_diff;
  s.speckleWindowSize = c.speckle_window_size;
  s.speckleRange = c.speckle_range;
  s.leftBand = c.left_band;
  m.kernelSize = c.median_kernel_size;
  m.minValidToFill = c.median_min_valid;
}

}  // namespace horopter::c_api

extern "C" {

const char* horopter_last_error(void) {
  return tLastError.c_str();
}

const char* horopter_status_name(horopter_status status) {
  switch (status) {
    case HOROPTER_OK:
      return "ok";
    case HOROPTER_ERROR_INVALID_ARGUMENT:
      return "invalid argument";
    case HOROPTER_ERROR_FAILED:
      return "failed";
    case HOROPTER_ERROR_OUT_OF_MEMORY:
      return "out of memory";
    case HOROPTER_ERROR_INTERNAL:
      return "internal error";
  }
  return "unknown status";
}

const char* horopter_version(void) {
  return HOROPTER_VERSION_STRING;
}

void horopter_stereo_params_default(horopter_stereo_params* params) {
  if (!params) return;
  const horopter::StereoParams s;
  const horopter::MedianParams m;
  params->min_disparity = s.minDisparity;
  params->num_disparities = s.numDisparities;
  params->block_size = s.blockSize;
  params->pre_filter_type = static_cast<int>(s.preFilterType);
  params->pre_filter_size = s.preFilterSize;
  params->pre_filter_cap = s.preFilterCap;
  params->texture_threshold = s.textureThreshold;
  params->uniqueness_ratio = s.uniquenessRatio;
  params->disp12_max_diff = s.disp12MaxDiff;
  params->speckle_window_size = s.speckleWindowSize;
  params->speckle_range = s.speckleRange;
  params->left_band = s.leftBand;
  params->median_kernel_size = m.kernelSize;
  params->median_min_valid = m.minValidToFill;
}

int horopter_backend_count(void) {
  return static_cast<int>(horopter::registeredBackends().size());
}

horopter_status horopter_backend_info(int index, const char** name, int* available) {
  return guarded([&] {
    const auto& all = horopter::registeredBackends();
    if (index < 0 || index >= static_cast<int>(all.size()))
      throw InvalidArgument("backend index " + std::to_string(index) + " is out of range 0.." +
                            std::to_string(static_cast<int>(all.size()) - 1));
    if (name) *name = all[static_cast<std::size_t>(index)]->name.c_str();
    if (available) *available = all[static_cast<std::size_t>(index)]->available ? 1 : 0;
  });
}

horopter_status horopter_matcher_create(const horopter_stereo_params* params, const char* backend,
                                        int threads, horopter_matcher** matcher) {
  return guarded([&] {
    requireNonNull(params, "params");
    requireNonNull(matcher, "matcher (the output handle)");
    *matcher = nullptr;
    horopter::StereoParams s;
    horopter::MedianParams m;
    paramsOf(*params, s, m);
    const horopter::Backend& b =
        horopter::findBackend(backend ? backend : horopter::FrontendDefaults::backend);
    *matcher = new horopter_matcher{horopter::StereoFrontend(s, m, b, threads)};
  });
}

void horopter_matcher_destroy(horopter_matcher* matcher) {
  delete matcher;
}

const char* horopter_matcher_backend(const horopter_matcher* matcher) {
  return matcher ? matcher->frontend.backend().name.c_str() : "";
}

horopter_status horopter_matcher_compute(horopter_matcher* matcher, const horopter_image* left,
                                         const horopter_image* right) {
  return guarded([&] {
    requireNonNull(matcher, "matcher");
    requireNonNull(left, "left image");
    requireNonNull(right, "right image");
    matcher->frontend.computeDisparity(viewOf(*left), viewOf(*right));
  });
}

horopter_status horopter_matcher_disparity(const horopter_matcher* matcher, horopter_image* out) {
  return guarded([&] {
    requireNonNull(matcher, "matcher");
    requireNonNull(out, "out");
    if (!matcher->frontend.hasDisparity())
      throw InvalidArgument(
          "no disparity: horopter_matcher_compute was not called, or its last call failed");
    *out = imageOf(matcher->frontend.disparity());
  });
}

horopter_status horopter_matcher_mask(horopter_matcher* matcher, const int16_t* thresholds,
                                      int count, const horopter_image* image) {
  return guarded([&] {
    requireNonNull(matcher, "matcher");
    requireNonNull(thresholds, "thresholds");
    if (count < 0) throw InvalidArgument("threshold count is negative");
    const horopter::ConstImageView view = image ? viewOf(*image) : horopter::ConstImageView{};
    matcher->frontend.computeMask({thresholds, static_cast<std::size_t>(count)}, view);
  });
}

horopter_status horopter_matcher_mask_result(const horopter_matcher* matcher, horopter_image* mask,
                                             horopter_image* segmented) {
  return guarded([&] {
    requireNonNull(matcher, "matcher");
    if (!matcher->frontend.hasMask())
      throw InvalidArgument(
          "no mask: horopter_matcher_mask was not called, or its last call failed");
    if (mask) *mask = imageOf(matcher->frontend.mask());
    if (segmented) *segmented = imageOf(matcher->frontend.segmented());
  });
}

horopter_status horopter_geometry_from_calibration(const char* path, horopter_geometry* geometry) {
  return guarded([&] {
    requireNonNull(path, "path");
    requireNonNull(geometry, "geometry");
    horopter::StereoCalibration calibration;
    try {
      calibration = horopter::loadStereoCalibration(path);
    } catch (const std::exception& e) {  // missing, unreadable or malformed: the message says which
      throw Failed(e.what());
    }
    const horopter::RectifiedGeometry g = horopter::rectifiedGeometry(calibration);
    geometry->focal_px = g.focalPx;
    geometry->cx = g.cx;
    geometry->cy = g.cy;
    geometry->baseline = g.baseline;
  });
}

horopter_status horopter_thresholds_from_disparity(const horopter_geometry* geometry, double u,
                                                   double disparity_px, int16_t* out, int width) {
  return guarded([&] {
    const horopter::RectifiedGeometry g = geometryOf(geometry);
    requireTable(out, width);
    copyTable(
        horopter::horopterThresholds(g, width, horopter::fixationFromDisparity(g, u, disparity_px)),
        out);
  });
}

horopter_status horopter_thresholds_at_distance(const horopter_geometry* geometry, double distance,
                                                int16_t* out, int width) {
  return guarded([&] {
    const horopter::RectifiedGeometry g = geometryOf(geometry);
    requireTable(out, width);
    const auto circle = horopter::viethMuellerCircle(
        g.baseline, horopter::fixationAtDistance(g.baseline, distance));
    horopter::horopterThresholds(g, circle, {out, static_cast<std::size_t>(width)});
  });
}

}  // extern "C"
