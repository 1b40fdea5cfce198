#include "opencl/launch.hpp"

#include <algorithm>

#include "prefilter/prefilter.hpp"
#include "sad/sad.hpp"

namespace horopter::opencl {

namespace {

// Per-pixel kernels run in work-groups of a fixed shape, so a driver that
// compiles per work-group size (PoCL) compiles each kernel once.
constexpr size_t kGroupWidth = 64;

size_t roundUp(size_t v, size_t to) {
  return (v + to - 1) / to * to;
}

template <typename T>
void setArg(cl_kernel k, cl_uint& index, const T& value) {
  check(clSetKernelArg(k, index++, sizeof(T), &value), "setting a kernel argument");
}

template <typename... Args>
void setArgs(cl_kernel k, const Args&... args) {
  cl_uint index = 0;
  (setArg(k, index, args), ...);
}

void enqueuePerPixel(cl_command_queue q, cl_kernel k, int width, RowRange rows, cl_event* event,
                     const char* what) {
  const size_t global[2] = {roundUp(static_cast<size_t>(width), kGroupWidth),
                            static_cast<size_t>(rows.end - rows.begin)};
  const size_t local[2] = {kGroupWidth, 1};
  check(clEnqueueNDRangeKernel(q, k, 2, nullptr, global, local, 0, nullptr, event), what);
}

}  // namespace

Buffer::~Buffer() {
  if (mem_) clReleaseMemObject(mem_);
}

cl_mem Buffer::get(cl_context context, std::size_t bytes) {
  bytes = std::max<std::size_t>(bytes, 1);
  if (mem_ && bytes_ >= bytes) return mem_;
  if (mem_) clReleaseMemObject(mem_);
  mem_ = nullptr;
  bytes_ = 0;
  cl_int err = CL_SUCCESS;
  mem_ = clCreateBuffer(context, CL_MEM_READ_WRITE, bytes, nullptr, &err);
  check(err, "allocating a device buffer");
  bytes_ = bytes;
  return mem_;
}

cl_event* Events::add() {
  events_.push_back(nullptr);
  return &events_.back();
}

void Events::clear() {
  for (cl_event e : events_)
    if (e) clReleaseEvent(e);
  events_.clear();
}

Kernels::Kernels(Device& device)
    : prefilter(createKernel(device, "prefilter_xsobel")),
      prefilterNormalized(createKernel(device, "prefilter_normalized")),
      sad(createKernel(device, "sad_match")),
      lrCheck(createKernel(device, "lr_check")),
      median(createKernel(device, "median_filter")),
      mask(createKernel(device, "horopter_mask")) {}

void writeRows(cl_command_queue q, cl_mem buffer, const ConstImageView& view, int r0, int r1,
               bool blocking, cl_event* event) {
  if (r1 <= r0) return;
  const size_t rowBytes = static_cast<size_t>(view.width) * pixelBytes(view.type);
  const size_t bufferOrigin[3] = {0, static_cast<size_t>(r0), 0};
  const size_t hostOrigin[3] = {0, 0, 0};
  const size_t region[3] = {rowBytes, static_cast<size_t>(r1 - r0), 1};
  check(clEnqueueWriteBufferRect(q, buffer, blocking ? CL_TRUE : CL_FALSE, bufferOrigin, hostOrigin,
                                 region, rowBytes, 0, static_cast<size_t>(view.strideBytes), 0,
                                 view.row<void>(r0), 0, nullptr, event),
        "uploading an image");
}

void readRows(cl_command_queue q, cl_mem buffer, const ImageView& view, int r0, int r1,
              bool blocking, cl_event* event) {
  if (r1 <= r0) return;
  const size_t rowBytes = static_cast<size_t>(view.width) * pixelBytes(view.type);
  const size_t bufferOrigin[3] = {0, static_cast<size_t>(r0), 0};
  const size_t hostOrigin[3] = {0, 0, 0};
  const size_t region[3] = {rowBytes, static_cast<size_t>(r1 - r0), 1};
  check(clEnqueueReadBufferRect(q, buffer, blocking ? CL_TRUE : CL_FALSE, bufferOrigin, hostOrigin,
                                region, rowBytes, 0, static_cast<size_t>(view.strideBytes), 0,
                                view.row<void>(r0), 0, nullptr, event),
        "downloading an image");
}

void enqueuePrefilter(cl_command_queue q, cl_kernel k, cl_mem src, int width, int height, int cap,
                      RowRange rows, cl_mem filtered, cl_mem texture, bool wantFiltered,
                      bool wantTexture, cl_event* event) {
  if (rows.end <= rows.begin) return;
  setArgs(k, src, width, width, height, cap, rows.begin, rows.end, filtered, texture, width,
          static_cast<int>(wantFiltered), static_cast<int>(wantTexture));
  enqueuePerPixel(q, k, width, rows, event, "running the prefilter");
}

void enqueuePrefilterNormalized(cl_command_queue q, cl_kernel k, cl_mem src, int width, int height,
                                int cap, int size, RowRange rows, cl_mem filtered, cl_mem texture,
                                bool wantFiltered, bool wantTexture, cl_event* event) {
  if (rows.end <= rows.begin) return;
  const NormalizedWeights w = normalizedWeights(size);
  setArgs(k, src, width, width, height, cap, size / 2, w.centre, w.mean, rows.begin, rows.end,
          filtered, texture, width, static_cast<int>(wantFiltered), static_cast<int>(wantTexture));
  enqueuePerPixel(q, k, width, rows, event, "running the normalized-response prefilter");
}

void enqueuePrefilterFor(cl_command_queue q, const Kernels& kernels, const StereoParams& p,
                         cl_mem src, int width, int height, RowRange rows, cl_mem filtered,
                         cl_mem texture, bool wantFiltered, bool wantTexture, cl_event* event) {
  if (p.preFilterType == PreFilterType::NormalizedResponse)
    enqueuePrefilterNormalized(q, kernels.prefilterNormalized.get(), src, width, height,
                               p.preFilterCap, p.preFilterSize, rows, filtered, texture,
                               wantFiltered, wantTexture, event);
  else
    enqueuePrefilter(q, kernels.prefilter.get(), src, width, height, p.preFilterCap, rows, filtered,
                     texture, wantFiltered && p.preFilterType != PreFilterType::None, wantTexture,
                     event);
}

void enqueueMatch(cl_command_queue q, cl_kernel k, const DeviceDesc& device, cl_context context,
                  cl_mem left, cl_mem right, cl_mem texture, int width, int height,
                  const StereoParams& params, const BelowRangeGuard& guard, RowRange rows,
                  cl_mem disparity, cl_mem winnerRight, SadScratch& scratch, cl_event* event) {
  const int count = rows.end - rows.begin;
  if (count <= 0) return;
  const MatchRegion region = matchRegion(width, height, params);
  const int radius = params.blockSize / 2;
  // A strip of rows per work-item: a few per compute unit on a CPU (the
  // first rows of a strip pay for its window), more on a GPU.
  const int wanted = static_cast<int>(device.computeUnits) * (device.gpu ? 16 : 2);
  const int strips = std::clamp(wanted, 1, count);
  const int stripRows = (count + strips - 1) / strips;
  const int used = (count + stripRows - 1) / stripRows;
  const size_t columns = static_cast<size_t>(std::max(region.x1 - region.x0 + 2 * radius, 1));
  cl_mem colsum = scratch.colsum.get(context, static_cast<size_t>(used) * columns *
                                                  static_cast<size_t>(params.numDisparities) * 4);
  cl_mem colTex = scratch.colTex.get(context, static_cast<size_t>(used) * columns * 4);
  cl_mem rightCost = scratch.rightCost.get(context, static_cast<size_t>(used) * width * 4);
  cl_mem rightD = scratch.rightD.get(context, static_cast<size_t>(used) * width * 4);
  const int guards = guardCount(params, guard);
  cl_mem guardColumns = scratch.guardColumns.get(
      context, static_cast<size_t>(used) * columns * static_cast<size_t>(guards) * 4);
  setArgs(k, left, right, texture, width, width, params.minDisparity, params.numDisparities, radius,
          params.textureThreshold, params.uniquenessRatio, region.x0, region.x1, region.y0,
          region.y1, rows.begin, rows.end, stripRows, disparity, winnerRight, width, colsum, colTex,
          rightCost, rightD, guard.step, guards, guardColumns);
  const size_t global = static_cast<size_t>(used);
  const size_t local = 1;
  check(clEnqueueNDRangeKernel(q, k, 1, nullptr, &global, &local, 0, nullptr, event),
        "running the matcher");
}

void enqueueLeftRightCheck(cl_command_queue q, cl_kernel k, cl_mem disparity, cl_mem winnerRight,
                           int width, const StereoParams& params, RowRange rows, cl_event* event) {
  if (rows.end <= rows.begin || params.disp12MaxDiff < 0) return;
  const cl_short invalid = invalidDisparity(params);
  setArgs(k, disparity, winnerRight, width, width, rows.begin, rows.end, params.disp12MaxDiff,
          invalid, params.minDisparity - 1);
  enqueuePerPixel(q, k, width, rows, event, "running the left-right check");
}

void enqueueMedian(cl_command_queue q, cl_kernel k, cl_mem src, cl_mem dst, int width, int height,
                   int kernelSize, int minValid, std::int16_t invalid, RowRange rows,
                   cl_event* event) {
  if (rows.end <= rows.begin) return;
  const cl_short inv = invalid;
  setArgs(k, src, dst, width, width, height, kernelSize, minValid, inv, rows.begin, rows.end);
  // One work-item per 8 pixels of a row (median.cl works in short8 vectors).
  enqueuePerPixel(q, k, (width + 7) / 8, rows, event, "running the median");
}

void enqueueMask(cl_command_queue q, cl_kernel k, cl_mem disparity, cl_mem thresholds, int width,
                 std::int16_t invalid, RowRange rows, cl_mem mask, cl_mem image, cl_mem segmented,
                 int channels, cl_event* event) {
  if (rows.end <= rows.begin) return;
  const cl_short inv = invalid;
  setArgs(k, disparity, width, thresholds, width, rows.begin, rows.end, inv, mask, width, image,
          segmented, width * std::max(channels, 1), channels);
  enqueuePerPixel(q, k, width, rows, event, "running the horopter mask");
}

}  // namespace horopter::opencl
