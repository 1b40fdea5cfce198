#include "opencl/sync_kernels.hpp"

#include <algorithm>
#include <array>
#include <memory>
#include <mutex>

#include "horopter/core/error.hpp"
#include "opencl/cpu_speckles.hpp"
#include "opencl/device.hpp"
#include "opencl/launch.hpp"

namespace horopter::opencl {

namespace {

// What one device's synchronous calls reuse from call to call.
struct State {
  Device* device = nullptr;
  std::unique_ptr<Kernels> kernels;
  Buffer in0, in1, in2, out0, out1, thresholds;
  SadScratch sad;
};

// Locks the device for one call and sets its state up on first use.
class Call {
 public:
  explicit Call(int index) : state_(stateOf(index)), lock_(state_.device->callMutex()) {
    if (!state_.kernels) state_.kernels = std::make_unique<Kernels>(*state_.device);
  }
  State& state() { return state_; }
  Kernels& kernels() { return *state_.kernels; }
  cl_command_queue queue() { return state_.device->queue(); }
  cl_context context() { return state_.device->context(); }

 private:
  static State& stateOf(int index) {
    static std::array<State, kMaxBackendDevices> states;
    static std::once_flag once;
    std::call_once(once, [] {
      for (int i = 0; i < kMaxBackendDevices && i < static_cast<int>(devices().size()); ++i)
        states[i].device = devices()[i];
    });
    return states[index];
  }
  State& state_;
  std::unique_lock<std::mutex> lock_;
};

std::size_t imageBytes(int width, int height, PixelType type) {
  return static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * pixelBytes(type);
}

void prefilter(int index, const ConstImageView& src, int cap, const ImageView& filtered,
               const ImageView& texture, RowRange rows) {
  Call call(index);
  State& s = call.state();
  const int w = src.width, h = src.height;
  const std::size_t bytes = imageBytes(w, h, PixelType::U8C1);
  cl_mem in = s.in0.get(call.context(), bytes);
  cl_mem outF = s.out0.get(call.context(), bytes);
  cl_mem outT = s.out1.get(call.context(), bytes);
  // The rows above and below the range (reflect-101 stays within them).
  writeRows(call.queue(), in, src, std::max(0, rows.begin - 1), std::min(h, rows.end + 1), false,
            nullptr);
  enqueuePrefilter(call.queue(), call.kernels().prefilter.get(), in, w, h, cap, rows, outF, outT,
                   !filtered.empty(), !texture.empty(), nullptr);
  if (!filtered.empty())
    readRows(call.queue(), outF, filtered, rows.begin, rows.end, true, nullptr);
  if (!texture.empty()) readRows(call.queue(), outT, texture, rows.begin, rows.end, true, nullptr);
}

void prefilterNormalized(int index, const ConstImageView& src, int cap, int size,
                         const ImageView& filtered, const ImageView& texture, RowRange rows) {
  Call call(index);
  State& s = call.state();
  const int w = src.width, h = src.height;
  const std::size_t bytes = imageBytes(w, h, PixelType::U8C1);
  cl_mem in = s.in0.get(call.context(), bytes);
  cl_mem outF = s.out0.get(call.context(), bytes);
  cl_mem outT = s.out1.get(call.context(), bytes);
  // The window's rows above and below the range (the edge replicates within them).
  const int r = size / 2;
  writeRows(call.queue(), in, src, std::max(0, rows.begin - r), std::min(h, rows.end + r), false,
            nullptr);
  enqueuePrefilterNormalized(call.queue(), call.kernels().prefilterNormalized.get(), in, w, h, cap,
                             size, rows, outF, outT, !filtered.empty(), !texture.empty(), nullptr);
  if (!filtered.empty())
    readRows(call.queue(), outF, filtered, rows.begin, rows.end, true, nullptr);
  if (!texture.empty()) readRows(call.queue(), outT, texture, rows.begin, rows.end, true, nullptr);
}

void match(int index, const ConstImageView& left, const ConstImageView& right,
           const ConstImageView& texture, const StereoParams& params, const BelowRangeGuard& guard,
           const ImageView& disparity, const ImageView& winnerRight, RowRange rows) {
  Call call(index);
  State& s = call.state();
  const int w = left.width, h = left.height;
  const int r = params.blockSize / 2;
  const std::size_t bytes = imageBytes(w, h, PixelType::U8C1);
  cl_mem l = s.in0.get(call.context(), bytes);
  cl_mem rt = s.in1.get(call.context(), bytes);
  cl_mem t = s.in2.get(call.context(), bytes);
  const int r0 = std::max(0, rows.begin - r), r1 = std::min(h, rows.end + r);
  writeRows(call.queue(), l, left, r0, r1, false, nullptr);
  writeRows(call.queue(), rt, right, r0, r1, false, nullptr);
  if (params.textureThreshold > 0) writeRows(call.queue(), t, texture, r0, r1, false, nullptr);
  const std::size_t outBytes = imageBytes(w, h, PixelType::S16C1);
  cl_mem d = s.out0.get(call.context(), outBytes);
  cl_mem wr = s.out1.get(call.context(), outBytes);
  enqueueMatch(call.queue(), call.kernels(), s.device->desc(), call.context(), l, rt, t, w, h,
               params, guard, rows, d, wr, s.sad, {});
  readRows(call.queue(), d, disparity, rows.begin, rows.end, false, nullptr);
  readRows(call.queue(), wr, winnerRight, rows.begin, rows.end, true, nullptr);
}

void leftRight(int index, const ImageView& disparity, const ConstImageView& winnerRight,
               const StereoParams& params, RowRange rows) {
  if (params.disp12MaxDiff < 0) return;
  Call call(index);
  State& s = call.state();
  const int w = disparity.width, h = disparity.height;
  const std::size_t bytes = imageBytes(w, h, PixelType::S16C1);
  cl_mem d = s.out0.get(call.context(), bytes);
  cl_mem wr = s.out1.get(call.context(), bytes);
  writeRows(call.queue(), d, disparity, rows.begin, rows.end, false, nullptr);
  writeRows(call.queue(), wr, winnerRight, rows.begin, rows.end, false, nullptr);
  enqueueLeftRightCheck(call.queue(), call.kernels().lrCheck.get(), d, wr, w, params, rows,
                        nullptr);
  readRows(call.queue(), d, disparity, rows.begin, rows.end, true, nullptr);
}

// On the CPU: the blob labelling is sequential across the whole frame.
void speckles(const ImageView& disparity, const StereoParams& params) {
  filterSpecklesOnCpu(disparity, params);
}

void median(int index, const ConstImageView& src, const ImageView& dst, int kernelSize,
            int minValid, std::int16_t invalid, RowRange rows) {
  Call call(index);
  State& s = call.state();
  const int w = src.width, h = src.height;
  const int half = kernelSize / 2;
  const std::size_t bytes = imageBytes(w, h, PixelType::S16C1);
  cl_mem in = s.in0.get(call.context(), bytes);
  cl_mem out = s.out0.get(call.context(), bytes);
  writeRows(call.queue(), in, src, std::max(0, rows.begin - half), std::min(h, rows.end + half),
            false, nullptr);
  enqueueMedian(call.queue(), call.kernels().median.get(), in, out, w, h, kernelSize, minValid,
                invalid, rows, nullptr);
  readRows(call.queue(), out, dst, rows.begin, rows.end, true, nullptr);
}

void mask(int index, const ConstImageView& disparity, std::span<const std::int16_t> thresholds,
          std::int16_t invalid, const ImageView& maskOut, const ConstImageView& image,
          const ImageView& segmented, RowRange rows) {
  Call call(index);
  State& s = call.state();
  const int w = disparity.width, h = disparity.height;
  const int channels = segmented.empty() ? 0 : static_cast<int>(pixelBytes(image.type));
  cl_mem d = s.in0.get(call.context(), imageBytes(w, h, PixelType::S16C1));
  cl_mem t = s.thresholds.get(call.context(), thresholds.size_bytes());
  cl_mem m = s.out0.get(call.context(), imageBytes(w, h, PixelType::U8C1));
  cl_mem img = s.in1.get(call.context(), imageBytes(w, h, PixelType::U8C3));
  cl_mem seg = s.out1.get(call.context(), imageBytes(w, h, PixelType::U8C3));
  writeRows(call.queue(), d, disparity, rows.begin, rows.end, false, nullptr);
  check(clEnqueueWriteBuffer(call.queue(), t, CL_FALSE, 0, thresholds.size_bytes(),
                             thresholds.data(), 0, nullptr, nullptr),
        "uploading the thresholds");
  if (channels > 0) writeRows(call.queue(), img, image, rows.begin, rows.end, false, nullptr);
  enqueueMask(call.queue(), call.kernels().mask.get(), d, t, w, invalid, rows, m, img, seg,
              channels, nullptr);
  if (channels > 0) readRows(call.queue(), seg, segmented, rows.begin, rows.end, false, nullptr);
  readRows(call.queue(), m, maskOut, rows.begin, rows.end, true, nullptr);
}

// Plain function pointers per device: the table has no context argument.
template <int I>
KernelTable tableFor() {
  KernelTable t;
  t.prefilterXSobel = [](const ConstImageView& src, int cap, const ImageView& f,
                         const ImageView& tex,
                         RowRange rows) { prefilter(I, src, cap, f, tex, rows); };
  t.prefilterNormalized = [](const ConstImageView& src, int cap, int size, const ImageView& f,
                             const ImageView& tex, RowRange rows) {
    prefilterNormalized(I, src, cap, size, f, tex, rows);
  };
  t.matchBlocks = [](const ConstImageView& l, const ConstImageView& r, const ConstImageView& tex,
                     const StereoParams& p, const BelowRangeGuard& guard, const ImageView& d,
                     const ImageView& wr,
                     RowRange rows) { match(I, l, r, tex, p, guard, d, wr, rows); };
  t.leftRightCheck = [](const ImageView& d, const ConstImageView& wr, const StereoParams& p,
                        RowRange rows) { leftRight(I, d, wr, p, rows); };
  t.filterSpeckles = speckles;
  t.medianFilter = [](const ConstImageView& src, const ImageView& dst, int k, int minValid,
                      std::int16_t invalid,
                      RowRange rows) { median(I, src, dst, k, minValid, invalid, rows); };
  t.horopterMask = [](const ConstImageView& d, std::span<const std::int16_t> th,
                      std::int16_t invalid, const ImageView& m, const ConstImageView& img,
                      const ImageView& seg,
                      RowRange rows) { mask(I, d, th, invalid, m, img, seg, rows); };
  return t;
}

template <int... I>
KernelTable tableAt(int index, std::integer_sequence<int, I...>) {
  KernelTable result{};
  ((index == I ? (result = tableFor<I>(), 0) : 0), ...);
  return result;
}

}  // namespace

KernelTable syncKernelTable(int index) {
  if (index < 0 || index >= kMaxBackendDevices)
    throw Error("OpenCL device index " + std::to_string(index) + " has no kernel table (at most " +
                std::to_string(kMaxBackendDevices) + " devices get a backend)");
  return tableAt(index, std::make_integer_sequence<int, kMaxBackendDevices>{});
}

}  // namespace horopter::opencl
