#include "opencl/launch.hpp"

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <string>

#include "horopter/core/error.hpp"
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

// A __local argument of `bytes` bytes.
struct LocalBytes {
  size_t bytes;
};

template <typename T>
void setArg(cl_kernel k, cl_uint& index, const T& value) {
  check(clSetKernelArg(k, index++, sizeof(T), &value), "setting a kernel argument");
}

void setArg(cl_kernel k, cl_uint& index, const LocalBytes& local) {
  check(clSetKernelArg(k, index++, local.bytes, nullptr), "setting a local-memory argument");
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
      sadCosts(createKernel(device, "sad_costs")),
      sadDecide(createKernel(device, "sad_decide")),
      sadBand(createKernel(device, "sad_band")),
      lrCheck(createKernel(device, "lr_check")),
      median(createKernel(device, "median_filter")),
      mask(createKernel(device, "horopter_mask")),
      device_(&device) {}

cl_kernel Kernels::costsFor(const TiledVariant& variant) const {
  const std::string options = variant.buildOptions();
  if (options.empty()) return sadCosts.get();
  KernelHandle& k = variantCosts_[options];
  if (!k) {
    cl_int err = CL_SUCCESS;
    k.reset(clCreateKernel(device_->program(options), "sad_costs", &err));
    check(err, ("creating kernel sad_costs (tiled variant " + variant.name + ")").c_str());
  }
  return k.get();
}

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

SadShape sadShape(const DeviceDesc& device) {
  const char* env = std::getenv("HOROPTER_OPENCL_SAD");
  const std::string value = env != nullptr ? env : "";
  if (value == "strip") return SadShape::Strip;
  if (value == "tiled") return SadShape::Tiled;
  if (value.empty() || value == "auto") return device.gpu ? SadShape::Tiled : SadShape::Strip;
  throw Error("HOROPTER_OPENCL_SAD='" + value +
              "' is not a SAD kernel shape: use strip (one work-item per strip of rows, for "
              "CPU devices), tiled (cost volume, for GPUs) or auto (tiled on a GPU)");
}

const char* sadShapeName(SadShape shape) {
  return shape == SadShape::Tiled ? "tiled" : "strip";
}

namespace {

cl_event* eventFor(const EventSink& events, const char* stage) {
  return events ? events(stage) : nullptr;
}

void enqueueMatchStrip(cl_command_queue q, cl_kernel k, const DeviceDesc& device,
                       cl_context context, cl_mem left, cl_mem right, cl_mem texture, int width,
                       int height, const StereoParams& params, const BelowRangeGuard& guard,
                       RowRange rows, cl_mem disparity, cl_mem winnerRight, SadScratch& scratch,
                       cl_event* event) {
  const int count = rows.end - rows.begin;
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

// The cost volume's work-group: the variant's shape (by default 64 columns,
// two warps' consecutive words, by 4 rows), fewer rows where the device
// allows fewer work-items for sad_costs; fixed per variant, so PoCL compiles
// each variant's sad_costs once.
size_t costTileHeight(cl_kernel k, const DeviceDesc& device, const TiledVariant& variant) {
  const auto width = static_cast<size_t>(variant.groupWidth);
  const auto height = static_cast<size_t>(variant.groupHeight);
  size_t most = 0;
  if (clGetKernelWorkGroupInfo(k, device.id, CL_KERNEL_WORK_GROUP_SIZE, sizeof most, &most,
                               nullptr) != CL_SUCCESS ||
      most == 0)
    return height;
  return std::clamp<size_t>(most / width, 1, height);
}
// Local memory sad_costs may take for its column sums.
constexpr size_t kCostLocalBytes = 32 * 1024;
// The most one band's cost volume may take (and the device's allocation
// limit): 1280x720 with 128 disparities needs 0.47 GB, one band.
constexpr size_t kMaxCostVolumeBytes = size_t{1} << 30;
std::atomic<size_t> g_bandBytes{0};  // setTiledBandBytes

void enqueueMatchTiled(cl_command_queue q, const Kernels& kernels, const DeviceDesc& device,
                       cl_context context, cl_mem left, cl_mem right, cl_mem texture, int width,
                       int height, const StereoParams& params, const BelowRangeGuard& guard,
                       RowRange rows, cl_mem disparity, cl_mem winnerRight, SadScratch& scratch,
                       const EventSink& events) {
  const MatchRegion region = matchRegion(width, height, params);
  const int radius = params.blockSize / 2;
  const int guards = guardCount(params, guard);
  const int useTexture = params.textureThreshold > 0 ? 1 : 0;
  const int planes = params.numDisparities + guards + useTexture;
  // uint16 costs where every cost (at most 255 * block^2, the texture's sum
  // too) stays below 0xFFFF, sad_tiled.cl's "does not count": blocks <= 15.
  const int narrow = 255 * params.blockSize * params.blockSize < 0xFFFF ? 1 : 0;
  const size_t rowBytes =
      static_cast<size_t>(planes) * static_cast<size_t>(width) * (narrow ? 2 : 4);
  size_t cap = kMaxCostVolumeBytes;
  if (device.maxAlloc > 0) cap = std::min<size_t>(cap, device.maxAlloc);
  if (g_bandBytes > 0) cap = g_bandBytes;
  const int bandRows =
      static_cast<int>(std::clamp<size_t>(cap / rowBytes, 1, static_cast<size_t>(height)));
  const int regionRows =
      std::max(0, std::min(region.y1, rows.end) - std::max(region.y0, rows.begin));
  cl_mem costs = scratch.costs.get(
      context, rowBytes * static_cast<size_t>(std::min(bandRows, std::max(regionRows, 1))));
  const int minD = params.minDisparity, numD = params.numDisparities;
  const TiledVariant variant = tiledVariant().forBlock(params.blockSize);
  for (int b0 = rows.begin; b0 < rows.end; b0 += bandRows) {
    const int b1 = std::min(rows.end, b0 + bandRows);
    const int yA = std::max(region.y0, b0);
    // No region rows where the region has no columns either.
    const int yB = region.x0 < region.x1 ? std::max(yA, std::min(region.y1, b1)) : yA;
    if (yA < yB) {
      cl_kernel k = kernels.costsFor(variant);
      const size_t tileWidth = static_cast<size_t>(variant.groupWidth);
      const size_t tileHeight = costTileHeight(k, device, variant);
      // Planes per pass: the variant's (sad_tiled.cl's SAD_TILED_PASS_PLANES)
      // at most, fewer where a pass's column sums would pass 32 KB of local
      // memory (by default 4 up to block 65, 1 at block 255).
      const size_t tileRows = tileHeight * static_cast<size_t>(variant.rows);
      const size_t planeBytes = (tileWidth + 2 * static_cast<size_t>(radius)) * tileRows * 4;
      const int perPass = static_cast<int>(std::clamp<size_t>(
          kCostLocalBytes / planeBytes, 1, static_cast<size_t>(variant.passPlanes)));
      setArgs(k, left, right, texture, width, width, minD, numD, radius, region.x0, region.x1, yA,
              yB, guard.step, guards, useTexture, perPass, narrow, costs,
              LocalBytes{planeBytes * static_cast<size_t>(perPass)});
      // A work-item per `rows` rows; with split, the third dimension runs
      // over groups of split passes.
      const int passes = (planes + perPass - 1) / perPass;
      const int planeGroups = variant.split > 0 ? (passes + variant.split - 1) / variant.split : 1;
      const size_t global[3] = {
          roundUp(static_cast<size_t>(region.x1 - region.x0), tileWidth),
          roundUp(static_cast<size_t>(yB - yA), tileRows) / static_cast<size_t>(variant.rows),
          static_cast<size_t>(planeGroups)};
      const size_t local[3] = {tileWidth, tileHeight, 1};
      check(clEnqueueNDRangeKernel(q, k, 3, nullptr, global, local, 0, nullptr,
                                   eventFor(events, "match costs")),
            "running the matcher's cost volume");
    }
    const RowRange band{b0, b1};
    cl_kernel decide = kernels.sadDecide.get();
    setArgs(decide, costs, narrow, width, minD, numD, params.textureThreshold,
            params.uniquenessRatio, region.x0, region.x1, yA, yB, b0, b1, guard.step, guards,
            disparity, winnerRight, width);
    enqueuePerPixel(q, decide, width, band, eventFor(events, "match decide"),
                    "running the matcher's decisions");
  }
}

// The left band (sad_band.cl), after the region's kernels over the same
// rows: scalar::matchLeftBand's work on the device buffers. Nothing where
// there is no band (leftBand 0, or the region empty or without a row here).
void enqueueMatchLeftBand(cl_command_queue q, cl_kernel k, const DeviceDesc& device,
                          cl_context context, cl_mem left, cl_mem right, cl_mem texture, int width,
                          int height, const StereoParams& params, const BelowRangeGuard& guard,
                          RowRange rows, cl_mem disparity, cl_mem winnerRight,
                          SadBandScratch& scratch, const EventSink& events) {
  const MatchRegion region = matchRegion(width, height, params);
  const int yA = std::max(region.y0, rows.begin);
  const int yB = std::min(region.y1, rows.end);
  if (region.empty() || region.bandX0 >= region.x0 || yA >= yB) return;
  const int radius = params.blockSize / 2;
  const int numD = params.numDisparities;
  // The columns matchLeftBand costs, and the right winners it writes.
  const scalar::ColumnWindow window = scalar::leftBandWindow(region, params, guard);
  const int costedEnd = std::min(region.x1, window.costedEnd);
  const int rightEnd = std::clamp(window.rightEnd, 0, width);
  const int count = yB - yA;
  // Strips of rows as the strip matcher's: each pays for its first window.
  const int wanted = static_cast<int>(device.computeUnits) * (device.gpu ? 16 : 2);
  const int strips = std::clamp(wanted, 1, count);
  const int stripRows = (count + strips - 1) / strips;
  const auto used = static_cast<size_t>((count + stripRows - 1) / stripRows);
  const auto pixels = static_cast<size_t>(costedEnd - region.bandX0);
  const size_t columns = pixels + 2 * static_cast<size_t>(radius);
  const auto disparities = static_cast<size_t>(numD);
  const auto guards = static_cast<size_t>(guardCount(params, guard));
  const auto w = static_cast<size_t>(width);
  cl_mem colsum = scratch.colsum.get(context, used * columns * disparities * 4);
  cl_mem colTex = scratch.colTex.get(context, used * columns * 4);
  cl_mem costs = scratch.costs.get(context, used * pixels * disparities * 4);
  cl_mem rightCost = scratch.rightCost.get(context, used * w * 4);
  cl_mem rightD = scratch.rightD.get(context, used * w * 4);
  cl_mem guardColumns = scratch.guardColumns.get(context, used * columns * guards * 4);
  cl_mem guardCosts = scratch.guardCosts.get(context, used * pixels * guards * 4);
  setArgs(k, left, right, texture, width, width, params.minDisparity, numD, radius,
          params.textureThreshold, params.uniquenessRatio, region.bandX0, region.x0, costedEnd,
          rightEnd, yA, yB, stripRows, disparity, winnerRight, width, colsum, colTex, costs,
          rightCost, rightD, guard.step, static_cast<int>(guards), guardColumns, guardCosts);
  const size_t global = used;
  const size_t local = 1;
  check(clEnqueueNDRangeKernel(q, k, 1, nullptr, &global, &local, 0, nullptr,
                               eventFor(events, "match left band")),
        "running the matcher's left band");
}

}  // namespace

void enqueueMatch(cl_command_queue q, const Kernels& kernels, const DeviceDesc& device,
                  cl_context context, cl_mem left, cl_mem right, cl_mem texture, int width,
                  int height, const StereoParams& params, const BelowRangeGuard& guard,
                  RowRange rows, cl_mem disparity, cl_mem winnerRight, SadScratch& scratch,
                  const EventSink& events) {
  if (rows.end <= rows.begin) return;
  if (sadShape(device) == SadShape::Tiled)
    enqueueMatchTiled(q, kernels, device, context, left, right, texture, width, height, params,
                      guard, rows, disparity, winnerRight, scratch, events);
  else
    enqueueMatchStrip(q, kernels.sad.get(), device, context, left, right, texture, width, height,
                      params, guard, rows, disparity, winnerRight, scratch,
                      eventFor(events, "match"));
  enqueueMatchLeftBand(q, kernels.sadBand.get(), device, context, left, right, texture, width,
                       height, params, guard, rows, disparity, winnerRight, scratch.band, events);
}

void setTiledBandBytes(std::size_t bytes) {
  g_bandBytes = bytes;
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
