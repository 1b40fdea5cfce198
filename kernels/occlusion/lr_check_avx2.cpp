// AVX2 lr check: bit-exact with the scalar reference.
//
// Strategy
//   Lanes: 16 pixels per step in 16-bit lanes. dl = (d + 8) >> 4 is
//   (d >> 4) + bit 3 of d, exact for any int16; xr = x - dl fits 16 bits for
//   rows narrower than kMaxWindowWidth; |dl - WR(xr)| saturates only where it
//   is at least 32767, above any disp12MaxDiff (<= 2047).
//   Window: where the pixels that look up (a valid d, xr in [0, W)) reach at
//   most 32 consecutive right pixels (neighbours of a surface differ by a
//   pixel or two), WR is loaded as 32 entries at the window's start and each
//   lane takes its entry by byte shuffles: no memory access depends on a
//   lane. Elsewhere (depth edges, random maps, rows under 32 pixels) the
//   step falls back to gathers, 8 pixels in 32-bit lanes: a masked 32-bit
//   gather of the int16 pair (xr - 1, xr), keeping the high half, so it never
//   reads past the row's last pixel; lanes with xr == 0 (whose pair would
//   start before the row) take WR(0) from a broadcast instead. The gathers
//   cost about 3.5 times the window's step (they were 4.9 % of a
//   1280x720/d128/w15 frame's disparity time).
//   Tails: a row of at least 16 pixels ends with one step placed flush
//   against the row end, overlapping the previous one; that is harmless
//   because the check is idempotent per pixel (a pixel it invalidated is
//   skipped, one it kept is kept again) and reads no other disparity.
//   Narrower rows take the scalar loop.
#include <immintrin.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>

#include "common/cpu_features.hpp"
#include "occlusion/occlusion.hpp"

namespace horopter::avx2 {

namespace {

constexpr int kStep = 16;
// xr = x + lane - dl in 16 bits needs x + 15 + 2048 < 32768.
constexpr int kMaxWindowWidth = 30000;

HOROPTER_AVX2_TARGET void scalarRow(std::int16_t* d, const std::int16_t* wr, int width,
                                    std::int16_t invalid, int noWinner, int maxDiff) {
  for (int x = 0; x < width; ++x) {
    if (d[x] == invalid) continue;
    const int dl = (d[x] + 8) >> 4;
    const int xr = x - dl;
    if (xr < 0 || xr >= width || wr[xr] == noWinner) continue;
    if (std::abs(dl - wr[xr]) > maxDiff) d[x] = invalid;
  }
}

// table[o] for 16 offsets o in [0, 32): both 128-bit halves of each
// quarter of the table, a byte shuffle of each, two bits of o choosing.
HOROPTER_AVX2_TARGET inline __m256i lookup32(const std::int16_t* table, __m256i o) {
  const __m256i a = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(table));
  const __m256i b = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(table + 16));
  // Bytes 2e and 2e + 1 of a half, e = o mod 8.
  const __m256i bytes = _mm256_add_epi16(
      _mm256_mullo_epi16(_mm256_and_si256(o, _mm256_set1_epi16(7)), _mm256_set1_epi16(0x0202)),
      _mm256_set1_epi16(0x0100));
  const auto pick = [&](__m256i v, int half) HOROPTER_AVX2_TARGET {
    return _mm256_shuffle_epi8(
        half == 0 ? _mm256_permute2x128_si256(v, v, 0x00) : _mm256_permute2x128_si256(v, v, 0x11),
        bytes);
  };
  const __m256i bit3 = _mm256_srai_epi16(_mm256_slli_epi16(o, 12), 15);
  const __m256i bit4 = _mm256_srai_epi16(_mm256_slli_epi16(o, 11), 15);
  const __m256i fromA = _mm256_blendv_epi8(pick(a, 0), pick(a, 1), bit3);
  const __m256i fromB = _mm256_blendv_epi8(pick(b, 0), pick(b, 1), bit3);
  return _mm256_blendv_epi8(fromA, fromB, bit4);
}

// The least of 16 unsigned 16-bit lanes.
HOROPTER_AVX2_TARGET inline int leastLane(__m256i v) {
  const __m128i m = _mm_min_epu16(_mm256_castsi256_si128(v), _mm256_extracti128_si256(v, 1));
  return _mm_cvtsi128_si32(_mm_minpos_epu16(m)) & 0xFFFF;
}

// The check of one row, gathers for 8 pixels at x (<= width - 8).
class GatherStep {
 public:
  HOROPTER_AVX2_TARGET GatherStep(const std::int16_t* wr, int width, std::int16_t invalid,
                                  int noWinner, int maxDiff)
      : gatherBase_(reinterpret_cast<const int*>(wr)),
        wr0_(_mm256_set1_epi32(wr[0])),
        invalid32_(_mm256_set1_epi32(invalid)),
        invalid16_(_mm_set1_epi16(invalid)),
        noWinner_(_mm256_set1_epi32(noWinner)),
        maxDiff_(_mm256_set1_epi32(maxDiff)),
        width_(_mm256_set1_epi32(width)) {}

  HOROPTER_AVX2_TARGET void operator()(std::int16_t* d, int x) const {
    const __m256i eight = _mm256_set1_epi32(8);
    const __m256i zero = _mm256_setzero_si256();
    const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    auto* at = reinterpret_cast<__m128i*>(d + x);
    const __m128i d16 = _mm_loadu_si128(at);
    const __m256i dv = _mm256_cvtepi16_epi32(d16);
    const __m256i dl = _mm256_srai_epi32(_mm256_add_epi32(dv, eight), 4);
    const __m256i xr = _mm256_sub_epi32(_mm256_add_epi32(_mm256_set1_epi32(x), lane), dl);
    const __m256i valid =
        _mm256_andnot_si256(_mm256_cmpeq_epi32(dv, invalid32_), _mm256_set1_epi32(-1));
    // 0 <= xr < width.
    const __m256i inRange =
        _mm256_andnot_si256(_mm256_cmpgt_epi32(zero, xr), _mm256_cmpgt_epi32(width_, xr));
    const __m256i use = _mm256_and_si256(valid, inRange);
    const __m256i atZero = _mm256_cmpeq_epi32(xr, zero);
    // Pairs (xr - 1, xr) at byte offset 2 * (xr - 1); the high half is WR(xr).
    const __m256i pairs =
        _mm256_mask_i32gather_epi32(zero, gatherBase_, _mm256_sub_epi32(xr, _mm256_set1_epi32(1)),
                                    _mm256_andnot_si256(atZero, use), 2);
    const __m256i w = _mm256_blendv_epi8(_mm256_srai_epi32(pairs, 16), wr0_, atZero);
    const __m256i hasWinner = _mm256_andnot_si256(_mm256_cmpeq_epi32(w, noWinner_), use);
    const __m256i tooFar = _mm256_cmpgt_epi32(_mm256_abs_epi32(_mm256_sub_epi32(dl, w)), maxDiff_);
    const __m256i reject = _mm256_and_si256(hasWinner, tooFar);
    const __m128i reject16 =
        _mm_packs_epi32(_mm256_castsi256_si128(reject), _mm256_extracti128_si256(reject, 1));
    _mm_storeu_si128(at, _mm_blendv_epi8(d16, invalid16_, reject16));
  }

 private:
  const int* gatherBase_;
  __m256i wr0_, invalid32_;
  __m128i invalid16_;
  __m256i noWinner_, maxDiff_, width_;
};

// The check of one row, 16 pixels at x (<= width - 16) from a window of
// 32 right pixels; false, having changed nothing, where the pixels that
// look up reach further (the row needs at least 32 pixels).
class WindowStep {
 public:
  HOROPTER_AVX2_TARGET WindowStep(const std::int16_t* wr, int width, std::int16_t invalid,
                                  int noWinner, int maxDiff)
      : wr_(wr),
        width_(width),
        invalid_(_mm256_set1_epi16(invalid)),
        noWinner_(_mm256_set1_epi16(static_cast<std::int16_t>(noWinner))),
        // |dl - WR| > maxDiff iff (unsigned) |dl - WR| >= maxDiff + 1.
        farFrom_(_mm256_set1_epi16(static_cast<std::int16_t>(maxDiff + 1))),
        widthV_(_mm256_set1_epi16(static_cast<std::int16_t>(width))) {}

  HOROPTER_AVX2_TARGET bool operator()(std::int16_t* d, int x) const {
    const __m256i one = _mm256_set1_epi16(1);
    const __m256i all = _mm256_set1_epi16(-1);
    const __m256i lane = _mm256_setr_epi16(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    auto* at = reinterpret_cast<__m256i*>(d + x);
    const __m256i dv = _mm256_loadu_si256(at);
    const __m256i dl =
        _mm256_add_epi16(_mm256_srai_epi16(dv, 4), _mm256_and_si256(_mm256_srli_epi16(dv, 3), one));
    const __m256i xr = _mm256_sub_epi16(
        _mm256_add_epi16(_mm256_set1_epi16(static_cast<std::int16_t>(x)), lane), dl);
    const __m256i use =
        _mm256_andnot_si256(_mm256_cmpeq_epi16(dv, invalid_),
                            _mm256_andnot_si256(_mm256_cmpgt_epi16(_mm256_setzero_si256(), xr),
                                                _mm256_cmpgt_epi16(widthV_, xr)));
    if (_mm256_testz_si256(use, use)) return true;  // nothing to look up
    // The used lanes' least and largest xr (both in [0, width)).
    const int low = leastLane(_mm256_or_si256(xr, _mm256_xor_si256(use, all)));
    const int high = 0xFFFF - leastLane(_mm256_xor_si256(_mm256_and_si256(xr, use), all));
    if (high - low >= 32) return false;
    const int base = std::min(low, width_ - 32);
    const __m256i w = lookup32(
        wr_ + base, _mm256_sub_epi16(xr, _mm256_set1_epi16(static_cast<std::int16_t>(base))));
    const __m256i hasWinner = _mm256_andnot_si256(_mm256_cmpeq_epi16(w, noWinner_), use);
    const __m256i diff = _mm256_abs_epi16(_mm256_subs_epi16(dl, w));
    const __m256i tooFar = _mm256_cmpeq_epi16(_mm256_max_epu16(diff, farFrom_), diff);
    _mm256_storeu_si256(at, _mm256_blendv_epi8(dv, invalid_, _mm256_and_si256(hasWinner, tooFar)));
    return true;
  }

 private:
  const std::int16_t* wr_;
  int width_;
  __m256i invalid_, noWinner_, farFrom_, widthV_;
};

}  // namespace

HOROPTER_AVX2_TARGET void leftRightCheck(const ImageView& disparity,
                                         const ConstImageView& winnerRight,
                                         const StereoParams& params, RowRange rows) {
  if (params.disp12MaxDiff < 0) return;
  const std::int16_t invalid = invalidDisparity(params);
  const int noWinner = params.minDisparity - 1;
  const int width = disparity.width;
  const bool windows = width >= 32 && width < kMaxWindowWidth;
  for (int y = rows.begin; y < rows.end; ++y) {
    auto* d = disparity.row<std::int16_t>(y);
    const auto* wr = winnerRight.row<std::int16_t>(y);
    if (width < kStep) {
      scalarRow(d, wr, width, invalid, noWinner, params.disp12MaxDiff);
      continue;
    }
    const WindowStep window(wr, width, invalid, noWinner, params.disp12MaxDiff);
    const GatherStep gather(wr, width, invalid, noWinner, params.disp12MaxDiff);
    for (int x = 0;; x += kStep) {
      x = std::min(x, width - kStep);
      if (!windows || !window(d, x)) {
        gather(d, x);
        gather(d, x + kStep / 2);
      }
      if (x == width - kStep) break;
    }
  }
}

}  // namespace horopter::avx2
