// Enqueueing the front-end kernels on a queue: buffers, row transfers and
// one function per kernel. Device images are tightly packed (row pitch =
// width * pixel bytes) and hold the whole frame; a call transfers and
// computes only the rows it needs. Shared by the synchronous kernel table
// and the asynchronous OpenCL front end.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "horopter/core/image.hpp"
#include "horopter/kernels/backend.hpp"
#include "horopter/kernels/kernels.hpp"
#include "horopter/kernels/stereo_params.hpp"
#include "opencl/cl_api.hpp"
#include "opencl/device.hpp"
#include "opencl/tiled_variant.hpp"

namespace horopter::opencl {

// A device buffer that grows on demand and is otherwise reused.
class Buffer {
 public:
  Buffer() = default;
  ~Buffer();
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;
  // At least `bytes` (1 at the least), reallocated only to grow.
  cl_mem get(cl_context context, std::size_t bytes);

 private:
  cl_mem mem_ = nullptr;
  std::size_t bytes_ = 0;
};

// An event list that releases its events.
class Events {
 public:
  Events() = default;
  ~Events() { clear(); }
  Events(const Events&) = delete;
  Events& operator=(const Events&) = delete;
  cl_event* add();  // a slot for an enqueue call's event
  void clear();
  const std::vector<cl_event>& list() const { return events_; }

 private:
  std::vector<cl_event> events_;
};

// The kernels of a device's program; one set per thread that enqueues.
struct Kernels {
  explicit Kernels(Device& device);
  KernelHandle prefilter, prefilterNormalized, sad, sadCosts, sadDecide, sadBand, lrCheck, median,
      mask;
  // sad_costs of a tuning variant's program (sadCosts for the default's
  // options), created on first use.
  cl_kernel costsFor(const TiledVariant& variant) const;

 private:
  Device* device_;
  mutable std::map<std::string, KernelHandle> variantCosts_;
};

// Where a launch's profiling events go: a slot for the event of the stage
// named, or nullptr (an empty sink: no events).
using EventSink = std::function<cl_event*(const char* stage)>;

// Rows [r0, r1) of `view` into the tight buffer / back from it.
void writeRows(cl_command_queue q, cl_mem buffer, const ConstImageView& view, int r0, int r1,
               bool blocking, cl_event* event);
void readRows(cl_command_queue q, cl_mem buffer, const ImageView& view, int r0, int r1,
              bool blocking, cl_event* event);

void enqueuePrefilter(cl_command_queue q, cl_kernel k, cl_mem src, int width, int height, int cap,
                      RowRange rows, cl_mem filtered, cl_mem texture, bool wantFiltered,
                      bool wantTexture, cl_event* event);

void enqueuePrefilterNormalized(cl_command_queue q, cl_kernel k, cl_mem src, int width, int height,
                                int cap, int size, RowRange rows, cl_mem filtered, cl_mem texture,
                                bool wantFiltered, bool wantTexture, cl_event* event);

// The prefilter `p` names (x-Sobel or normalized response, the x-Sobel texture
// for None), as kernels.hpp's prefilter(): both front ends' one dispatch.
void enqueuePrefilterFor(cl_command_queue q, const Kernels& kernels, const StereoParams& p,
                         cl_mem src, int width, int height, RowRange rows, cl_mem filtered,
                         cl_mem texture, bool wantFiltered, bool wantTexture, cl_event* event);

// The SAD matcher's two shapes (same outputs, bit for bit): Strip, one
// work-item per strip of rows (sad.cl, for CPU devices), and Tiled, a cost
// volume and per-pixel kernels (sad_tiled.cl, for GPUs).
enum class SadShape { Strip, Tiled };
// HOROPTER_OPENCL_SAD=strip|tiled|auto (unset or empty: auto): auto takes
// Tiled on a GPU and Strip elsewhere. Any other value is a horopter::Error.
SadShape sadShape(const DeviceDesc& device);
// The tiled shape's cost-kernel variant is HOROPTER_OPENCL_TILED's:
// tiledVariant() (tiled_variant.hpp), for tuning sweeps.
const char* sadShapeName(SadShape shape);

// Scratch of the matcher's left band (sad_band.cl), per strip of rows.
struct SadBandScratch {
  Buffer colsum, colTex, costs, rightCost, rightD, guardColumns, guardCosts;
};
// Scratch of the matcher: per strip of rows (Strip), the cost volume (Tiled),
// and the left band's.
struct SadScratch {
  Buffer colsum, colTex, rightCost, rightD, guardColumns, costs;
  SadBandScratch band;
};
// Events: "match" (Strip), or "match costs" and "match decide" (Tiled; once
// per band of rows when the cost volume of all the rows would pass the
// device's allocation limit); then "match left band" where params.leftBand
// leaves a band (sad_band.cl, after either shape).
void enqueueMatch(cl_command_queue q, const Kernels& kernels, const DeviceDesc& device,
                  cl_context context, cl_mem left, cl_mem right, cl_mem texture, int width,
                  int height, const StereoParams& params, const BelowRangeGuard& guard,
                  RowRange rows, cl_mem disparity, cl_mem winnerRight, SadScratch& scratch,
                  const EventSink& events);
// Test hook: while non-zero, the most bytes one band of the tiled matcher's
// cost volume may take (0: the default, 1 GiB or the device's limit).
void setTiledBandBytes(std::size_t bytes);

void enqueueLeftRightCheck(cl_command_queue q, cl_kernel k, cl_mem disparity, cl_mem winnerRight,
                           int width, const StereoParams& params, RowRange rows, cl_event* event);

void enqueueMedian(cl_command_queue q, cl_kernel k, cl_mem src, cl_mem dst, int width, int height,
                   int kernelSize, int minValid, std::int16_t invalid, RowRange rows,
                   cl_event* event);

// `channels` 0 (no segmented image), 1 or 3.
void enqueueMask(cl_command_queue q, cl_kernel k, cl_mem disparity, cl_mem thresholds, int width,
                 std::int16_t invalid, RowRange rows, cl_mem mask, cl_mem image, cl_mem segmented,
                 int channels, cl_event* event);

}  // namespace horopter::opencl
