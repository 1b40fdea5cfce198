#include "opencl/pipeline.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstring>

#include "horopter/core/error.hpp"
#include "opencl/cpu_speckles.hpp"
#include "opencl/device.hpp"
#include "opencl/launch.hpp"
#include "opencl/opencl_backend.hpp"

namespace horopter::opencl {

namespace {

std::atomic<bool> g_failEnqueue{false};

double eventMs(cl_event e) {
  cl_ulong start = 0, end = 0;
  if (clGetEventProfilingInfo(e, CL_PROFILING_COMMAND_START, sizeof start, &start, nullptr) !=
          CL_SUCCESS ||
      clGetEventProfilingInfo(e, CL_PROFILING_COMMAND_END, sizeof end, &end, nullptr) != CL_SUCCESS)
    return 0;
  return static_cast<double>(end - start) * 1e-6;
}

}  // namespace

struct Pipeline::Impl {
  struct Slot {
    Buffer left, right, leftFiltered, rightFiltered, texture, disparity, winner, median;
    SadScratch sad;
    Image clean;  // the left-right checked map, for the CPU speckle filter
    Image* out = nullptr;
    StereoParams stereo;  // this frame's (its search range)
    int width = 0, height = 0;
    bool pending = false;
    Events events;
    std::vector<const char*> names;  // one per event
    cl_event* add(const char* name) {
      names.push_back(name);
      return events.add();
    }
  };

  Device* device = nullptr;
  MedianParams median;
  cl_command_queue queue = nullptr;
  std::unique_ptr<Kernels> kernels;
  std::vector<Slot> slots;
};

Pipeline::Pipeline(const std::string& backendName, const StereoParams& stereo,
                   const MedianParams& median, int slots)
    : impl_(std::make_unique<Impl>()) {
  validate(stereo);
  validate(median);
  const int index = deviceIndexOf(backendName);
  if (index < 0 || index >= static_cast<int>(devices().size()))
    throw Error("'" + backendName + "' is not an OpenCL device here");
  Impl& s = *impl_;
  s.device = devices()[static_cast<std::size_t>(index)];
  s.median = median;
  sadShape(s.device->desc());  // a bad HOROPTER_OPENCL_SAD fails here, not at the first frame
  tiledVariant();              // and a bad HOROPTER_OPENCL_TILED
  s.kernels = std::make_unique<Kernels>(*s.device);  // builds the program (or throws)
  s.queue = createQueue(*s.device);
  s.slots = std::vector<Impl::Slot>(static_cast<std::size_t>(slots));
}

Pipeline::~Pipeline() {
  if (impl_->queue) {
    clFinish(impl_->queue);
    impl_->slots.clear();
    clReleaseCommandQueue(impl_->queue);
  }
}

const std::string& Pipeline::deviceName() const {
  return impl_->device->desc().name;
}

void Pipeline::submit(int index, const ConstImageView& left, const ConstImageView& right,
                      const StereoParams& stereo, const BelowRangeGuard& guard, Image& out) {
  Impl& s = *impl_;
  Impl::Slot& slot = s.slots[static_cast<std::size_t>(index)];
  if (g_failEnqueue)
    throw Error("OpenCL: enqueueing the frame failed: injected enqueue failure (test hook)");
  if (slot.pending) {
    std::vector<OpenClStageTime> ignored;
    wait(index, ignored);
  }
  slot.events.clear();
  slot.names.clear();
  const int w = left.width, h = left.height;
  validate(stereo);
  const StereoParams& p = stereo;
  cl_context ctx = s.device->context();
  cl_command_queue q = s.queue;
  const std::size_t u8 = static_cast<std::size_t>(w) * h, s16 = u8 * 2;
  const RowRange all{0, h};

  cl_mem l = slot.left.get(ctx, u8), r = slot.right.get(ctx, u8);
  cl_mem lf = slot.leftFiltered.get(ctx, u8), rf = slot.rightFiltered.get(ctx, u8);
  cl_mem tex = slot.texture.get(ctx, u8);
  cl_mem d = slot.disparity.get(ctx, s16), wr = slot.winner.get(ctx, s16);
  writeRows(q, l, left, 0, h, false, slot.add("upload left"));
  writeRows(q, r, right, 0, h, false, slot.add("upload right"));
  const bool filter = p.preFilterType != PreFilterType::None;
  const bool wantTexture = p.textureThreshold > 0;
  if (filter) {
    enqueuePrefilterFor(q, *s.kernels, p, l, w, h, all, lf, tex, true, wantTexture,
                        slot.add("prefilter left"));
    enqueuePrefilterFor(q, *s.kernels, p, r, w, h, all, rf, tex, true, false,
                        slot.add("prefilter right"));
  } else if (wantTexture) {
    enqueuePrefilterFor(q, *s.kernels, p, l, w, h, all, lf, tex, false, true, slot.add("texture"));
  }
  enqueueMatch(q, *s.kernels, s.device->desc(), ctx, filter ? lf : l, filter ? rf : r, tex, w, h, p,
               guard, all, d, wr, slot.sad, [&slot](const char* stage) { return slot.add(stage); });
  if (p.disp12MaxDiff >= 0)
    enqueueLeftRightCheck(q, s.kernels->lrCheck.get(), d, wr, w, p, all,
                          slot.add("left-right check"));
  slot.out = &out;
  slot.stereo = stereo;
  slot.width = w;
  slot.height = h;
  if (p.speckleWindowSize > 0) {
    // The speckle filter runs on the CPU in wait(): bring the map back.
    if (slot.clean.width() != w || slot.clean.height() != h)
      slot.clean = Image(w, h, PixelType::S16C1);
    readRows(q, d, slot.clean.view(), 0, h, false, slot.add("download"));
  } else if (s.median.kernelSize > 0) {
    cl_mem m = slot.median.get(ctx, s16);
    enqueueMedian(q, s.kernels->median.get(), d, m, w, h, s.median.kernelSize,
                  effectiveMinValid(s.median), invalidDisparity(p), all, slot.add("median"));
    readRows(q, m, out.view(), 0, h, false, slot.add("download"));
  } else {
    readRows(q, d, out.view(), 0, h, false, slot.add("download"));
  }
  check(clFlush(q), "submitting the frame");
  slot.pending = true;
}

void Pipeline::wait(int index, std::vector<OpenClStageTime>& times) {
  Impl& s = *impl_;
  Impl::Slot& slot = s.slots[static_cast<std::size_t>(index)];
  times.clear();
  if (!slot.pending) return;
  slot.pending = false;
  const auto& events = slot.events.list();
  check(clWaitForEvents(static_cast<cl_uint>(events.size()), events.data()),
        "waiting for the frame");
  // A stage enqueued more than once (the tiled matcher's bands) is one entry.
  for (std::size_t i = 0; i < events.size(); ++i) {
    const auto same = std::find_if(times.begin(), times.end(), [&](const OpenClStageTime& t) {
      return t.stage == slot.names[i];
    });
    if (same != times.end())
      same->ms += eventMs(events[i]);
    else
      times.push_back({slot.names[i], eventMs(events[i]), true});
  }
  if (slot.stereo.speckleWindowSize == 0) return;

  const auto start = std::chrono::steady_clock::now();
  const Backend& cpu = filterSpecklesOnCpu(slot.clean.view(), slot.stereo);
  times.push_back(
      {"speckle filter (CPU, " + cpu.name + ")",
       std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count(),
       false});
  const int w = slot.width, h = slot.height;
  ImageView out = slot.out->view();
  if (s.median.kernelSize == 0) {
    for (int y = 0; y < h; ++y)
      std::memcpy(out.row<void>(y), slot.clean.view().row<void>(y),
                  static_cast<std::size_t>(w) * 2);
    return;
  }
  cl_context ctx = s.device->context();
  const std::size_t s16 = static_cast<std::size_t>(w) * h * 2;
  cl_mem d = slot.disparity.get(ctx, s16), m = slot.median.get(ctx, s16);
  Events more;
  writeRows(s.queue, d, slot.clean.view(), 0, h, false, more.add());
  enqueueMedian(s.queue, s.kernels->median.get(), d, m, w, h, s.median.kernelSize,
                effectiveMinValid(s.median), invalidDisparity(slot.stereo), {0, h}, more.add());
  readRows(s.queue, m, out, 0, h, true, more.add());
  const char* names[] = {"upload cleaned", "median", "download median"};
  for (std::size_t i = 0; i < more.list().size(); ++i)
    times.push_back({names[i], eventMs(more.list()[i]), true});
}

void setInjectedEnqueueFailure(bool on) {
  g_failEnqueue = on;
}

}  // namespace horopter::opencl
