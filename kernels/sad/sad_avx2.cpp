// AVX2 SAD block matching: bit-exact with the scalar reference.
//
// Strategy
//   Per output row, three passes over the region's pixels (i = x - x0, P of
//   them), with 16-bit costs biased by 0x8000 so that signed compares and min
//   order them as unsigned. The passes go tile by tile (128 pixels): the
//   sweep of every group over the tile, its left decisions, then the right
//   winners whose pixels are all swept, so the costs read are still cached.
//
//   Overflow bound: a window cost is at most maxDiff * blockSize^2, maxDiff
//   bounding |L - R| from the inputs' actual value ranges (scanned over the
//   rows this call reads). Unless that is below 65535 (raw images with blocks
//   over 15, x-Sobel inputs with blocks over 31 or so), the call forwards to
//   the scalar reference. Otherwise every sum is exact: 16-bit lanes wrap
//   modulo 2^16, but every true value they stand for fits, and 65535 is free
//   to mark "no cost" (above every real cost, never within a limit).
//
//   Keys: where the bound leaves room, a cost C of lane k is kept as the key
//   G * C + q, q = k / Q with Q = count / G, G = 2^s with the largest s <= 3
//   such that G * bound + G - 1 < 65535 (s = 3 for x-Sobel inputs with
//   blocks up to 11, s = 0, plain costs, near the limit). The sums carry it
//   for free: column sums add G * |L - R| and the window sums start at
//   bias + q, so the low s bits never change. Over the G lanes j, j + Q, ..
//   (group j), the least key is the least cost at its smallest k, by a
//   plain min; the winner searches take that per group and merge the groups
//   in increasing j with a strict < on the whole key, so ties still go to
//   the smallest d (leastKeys). C <= limit iff key <= G * limit + G - 1.
//   Costs are read back as key >> s; "no cost" stays 65535.
//
//   1. Sweep (running sums, OpenCV's StereoBM scheme), one group of 16
//      disparities at a time (lanes d = minD + 16g + k): columnSum[g][x]
//      holds a column's costs over the window's height and slides down a row
//      by adding |L - R| of the entering row and subtracting that of the
//      leaving one. The right rows are copied reversed, so the pixels x - d
//      of 16 consecutive d are 16 consecutive bytes, and then the entering
//      and leaving rows' bytes are interleaved (as are the left pixels, one
//      16-bit word per column): per pixel and group, one broadcast of the
//      left word, |L - R| of both rows in one byte vector (saturating
//      subtractions both ways, or; where every |L - R| <= 127, as with
//      x-Sobel inputs, the absolute value of the wrapped byte difference)
//      and maddubs with (G, -G) give
//      G * (in - out) in 16-bit lanes in natural order. Along x, the window
//      cost takes in column x + r and drops column x - r - 1 (a zero column
//      left of the first makes warming up the same step). Groups go two at a
//      time (32 disparities, sharing the broadcast); an odd last group alone.
//      Every 16 pixels, their 16 cost vectors are transposed in registers
//      and stored by lane: costs[k][i]. A pair does it every 8 pixels,
//      one group after the other (the left pixels broadcast twice), its 8
//      vectors transposed within 128-bit lanes and stored as halves (rows
//      k and k + 8), so that 8 cost vectors are live, not 32.
//   2. Left decisions, 16 pixels per vector (4 vectors per pass): the least
//      key over the lanes as above, so the smallest d wins ties; the
//      uniqueness limit (32-bit, the /100 as a multiplication in double,
//      exact); the count of lanes with cost <= limit, which for a valid
//      pixel is the winner plus those of its neighbours within the limit.
//      Then, from the registers, 16 pixels at a time: the neighbours' costs
//      C(b - 1), C(b + 1) by gathers (rows -1 and D hold "no cost"), texture
//      (window sums of 16-bit column sums), uniqueness in 16-bit lanes, and
//      sub-pixel (truncated division in float, exact for these magnitudes)
//      and rounding in two halves of 8 pixels.
//   3. Right winners, 16 right pixels per vector: right pixel xr meets lane k
//      at pixel xr + minD + k - x0, so lane k's costs for 16 consecutive xr
//      are 16 consecutive entries of its row (unaligned load; edges of "no
//      cost" around each row). The least key over increasing k, as above,
//      keeps the smallest d on ties, as the reference does.
//
//   4. Guard below the range (zone-limited matching, when on). With step 1
//      (the default) or 2, the sweep takes the K checked disparities' span
//      as ceil(K * step / 16) more groups below the range's (lanes k < 0,
//      rows -1, -2, ... of costs; the reversed right rows are padded in
//      front for their reads past the image's right edge). After each
//      tile's sweep, fixGuardTile writes "no cost" where a lane is not
//      checked (below `lowest`, or between two checked ones) or does not
//      count (its window reaches past the right image), and the least per
//      pixel for finishLeft; the right winners take their least key over
//      those lanes (leastKeys, the smallest g on ties) where its cost is <=
//      the range's least. With a larger step: per checked disparity, 16-bit
//      column sums of |L - R| slide down the rows as the others do (16
//      columns per vector, the right pixels read in place), and each row's
//      window sums (2r + 1 column loads per 16 pixels) fold
//      into the least per pixel, 65535 where none counts. finishLeft then
//      invalidates a pixel whose least is <= its uniqueness limit (the
//      winner's cost when the test is off), unsigned in 16 bits: these costs
//      obey the same bound. The window sums stay in one row per checked
//      disparity (65535 outside the pixels where it counts, and on wide
//      edges), so that decideRight reads right pixel xr's candidates at
//      entries xr + g - x0, in increasing g, and takes the least where it
//      is <= the range's least.
//
//   Tails: the last block of pixels is padded with "no cost" lanes; image
//   rows are read only within [0, width), and outputs are written only in the
//   rows asked for (every pixel of them, as the reference). Memory per call
//   is O(width * numDisparities): nothing is kept per image row.
#include <immintrin.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <new>
#include <numeric>
#include <type_traits>
#include <vector>

#include "common/cpu_features.hpp"
#include "sad/sad.hpp"
#include "sad/sad_transpose_avx2.hpp"

namespace horopter::avx2 {

namespace {

constexpr int kLanes = 16;  // 16-bit lanes per vector
constexpr std::uint16_t kBias = 0x8000;
constexpr std::int16_t kNoCost = 0x7FFF;  // 65535 biased: above every real cost (< 65535)

// A 64-byte aligned array, every element `value` (zero by default).
template <typename T>
class AlignedArray {
 public:
  HOROPTER_AVX2_TARGET explicit AlignedArray(std::size_t n, T value = T{})
      : data_(static_cast<T*>(
            ::operator new[](std::max<std::size_t>(n, 1) * sizeof(T), std::align_val_t{64}))) {
    std::fill_n(data_, n, value);
  }
  ~AlignedArray() { ::operator delete[](data_, std::align_val_t{64}); }
  AlignedArray(const AlignedArray&) = delete;
  AlignedArray& operator=(const AlignedArray&) = delete;
  T* get() const { return data_; }

 private:
  T* data_;
};

HOROPTER_AVX2_TARGET inline __m256i load(const std::int16_t* p) {
  return _mm256_load_si256(reinterpret_cast<const __m256i*>(p));
}
HOROPTER_AVX2_TARGET inline void store(std::int16_t* p, __m256i v) {
  _mm256_store_si256(reinterpret_cast<__m256i*>(p), v);
}
HOROPTER_AVX2_TARGET inline __m256i loadu(const std::uint8_t* p) {
  return _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p));
}
HOROPTER_AVX2_TARGET inline __m128i loadu128(const std::uint8_t* p) {
  return _mm_loadu_si128(reinterpret_cast<const __m128i*>(p));
}
// 16 bytes widened to 16-bit lanes.
HOROPTER_AVX2_TARGET inline __m256i widen(const std::uint8_t* p) {
  return _mm256_cvtepu8_epi16(loadu128(p));
}
// |a - b| per byte.
HOROPTER_AVX2_TARGET inline __m256i absDiff8(__m256i a, __m256i b) {
  return _mm256_or_si256(_mm256_subs_epu8(a, b), _mm256_subs_epu8(b, a));
}
// |a - b| per byte where every true difference a - b lies in [-127, 127]
// (kNarrow: x-Sobel inputs, 0 .. 2 * preFilterCap <= 126): the wrapped
// signed difference is exact, so its absolute value takes 2 instructions
// instead of absDiff8's 3.
template <bool kNarrow>
[[gnu::always_inline]] HOROPTER_AVX2_TARGET inline __m256i absDiffRows(__m256i a, __m256i b) {
  if constexpr (kNarrow)
    return _mm256_abs_epi8(_mm256_sub_epi8(a, b));
  else
    return absDiff8(a, b);
}
HOROPTER_AVX2_TARGET inline __m256i load8x32(const int* p) {
  return _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p));
}

// min and max byte of rows [y0, y1) of a U8C1 view, folded into lo and hi.
HOROPTER_AVX2_TARGET void scanRange(const ConstImageView& view, int y0, int y1, int& lo, int& hi) {
  __m256i vmin = _mm256_set1_epi8(-1), vmax = _mm256_setzero_si256();
  for (int y = y0; y < y1; ++y) {
    const auto* p = view.row<std::uint8_t>(y);
    int x = 0;
    for (; x + 32 <= view.width; x += 32) {
      const __m256i v = loadu(p + x);
      vmin = _mm256_min_epu8(vmin, v);
      vmax = _mm256_max_epu8(vmax, v);
    }
    for (; x < view.width; ++x) {
      lo = std::min<int>(lo, p[x]);
      hi = std::max<int>(hi, p[x]);
    }
  }
  alignas(32) std::uint8_t mins[32], maxs[32];
  _mm256_store_si256(reinterpret_cast<__m256i*>(mins), vmin);
  _mm256_store_si256(reinterpret_cast<__m256i*>(maxs), vmax);
  for (int i = 0; i < 32; ++i) {
    lo = std::min<int>(lo, mins[i]);
    hi = std::max<int>(hi, maxs[i]);
  }
}

// dst[i] = src[width - 1 - i] for i in [0, width).
HOROPTER_AVX2_TARGET void reverseRow(const std::uint8_t* src, int width, std::uint8_t* dst) {
  const __m256i flip = _mm256_setr_epi8(15, 14, 13, 12, 11, 10, 9, 8, 7, 6, 5, 4, 3, 2, 1, 0, 15,
                                        14, 13, 12, 11, 10, 9, 8, 7, 6, 5, 4, 3, 2, 1, 0);
  int i = 0;
  for (; i + 32 <= width; i += 32) {
    const __m256i v = _mm256_shuffle_epi8(loadu(src + width - 32 - i), flip);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(dst + i), _mm256_permute4x64_epi64(v, 0x4E));
  }
  for (; i < width; ++i)
    dst[i] = src[width - 1 - i];
}

// dst[2i] = a[i], dst[2i + 1] = b[i] for i in [0, n).
HOROPTER_AVX2_TARGET void interleaveBytes(const std::uint8_t* a, const std::uint8_t* b, int n,
                                          std::uint8_t* dst) {
  int i = 0;
  for (; i + 32 <= n; i += 32) {
    const __m256i va = loadu(a + i), vb = loadu(b + i);
    const __m256i lo = _mm256_unpacklo_epi8(va, vb), hi = _mm256_unpackhi_epi8(va, vb);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(dst + 2 * i),
                        _mm256_permute2x128_si256(lo, hi, 0x20));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(dst + 2 * i + 32),
                        _mm256_permute2x128_si256(lo, hi, 0x31));
  }
  for (; i < n; ++i) {
    dst[2 * i] = a[i];
    dst[2 * i + 1] = b[i];
  }
}

// Stores transpose8x16's w[c] for 8 pixels: low half to row c, high half
// to row c + 8 (rows rowLen entries apart, from `row`, 16-byte aligned).
// Written as asm so that the 16 rows are addressed from `row` and three
// bases computed on the way (rows 4, 8, 12), with the stride S or 3S as a
// scaled index: 3 address computations per 16 stores. From C++, GCC either
// kept the 16 row addresses as loop invariants, spilled to the stack, or
// (the stride hidden from it) walked a pointer with one add per row.
[[gnu::always_inline]] HOROPTER_AVX2_TARGET inline void storeHalves(std::int16_t* row,
                                                                    std::ptrdiff_t rowLen,
                                                                    const __m256i* w) {
  const std::ptrdiff_t s = rowLen * static_cast<std::ptrdiff_t>(sizeof(std::int16_t));
  const std::ptrdiff_t s3 = 3 * s;
  std::int16_t* t;
  asm volatile(
      "vmovdqa %x[w0], (%[b])\n\t"
      "vmovdqa %x[w1], (%[b],%[s])\n\t"
      "vmovdqa %x[w2], (%[b],%[s],2)\n\t"
      "vmovdqa %x[w3], (%[b],%[s3])\n\t"
      "vmovdqa %x[w4], (%[b],%[s],4)\n\t"
      "vmovdqa %x[w6], (%[b],%[s3],2)\n\t"
      "vextracti128 $1, %[w0], (%[b],%[s],8)\n\t"
      "vextracti128 $1, %[w4], (%[b],%[s3],4)\n\t"
      "lea (%[b],%[s],4), %[t]\n\t"  // row 4
      "vmovdqa %x[w5], (%[t],%[s])\n\t"
      "vmovdqa %x[w7], (%[t],%[s3])\n\t"
      "lea (%[b],%[s],8), %[t]\n\t"  // row 8
      "vextracti128 $1, %[w1], (%[t],%[s])\n\t"
      "vextracti128 $1, %[w2], (%[t],%[s],2)\n\t"
      "vextracti128 $1, %[w3], (%[t],%[s3])\n\t"
      "vextracti128 $1, %[w6], (%[t],%[s3],2)\n\t"
      "lea (%[b],%[s3],4), %[t]\n\t"  // row 12
      "vextracti128 $1, %[w5], (%[t],%[s])\n\t"
      "vextracti128 $1, %[w7], (%[t],%[s3])"
      : [t] "=&r"(t)
      : [b] "r"(row), [s] "r"(s), [s3] "r"(s3), [w0] "x"(w[0]), [w1] "x"(w[1]), [w2] "x"(w[2]),
        [w3] "x"(w[3]), [w4] "x"(w[4]), [w5] "x"(w[5]), [w6] "x"(w[6]), [w7] "x"(w[7])
      : "memory");
}

// Eight int32 lanes divided by 100, truncated (0 <= n < 2^31), without a
// division: (n + 0.5) / 100 lies at least 0.005 from an integer, and
// (n + 0.5) * 0.01 in double is within 2^-26 of it, so truncating it gives
// floor(n / 100).
HOROPTER_AVX2_TARGET inline __m256i divideBy100(__m256i n) {
  const __m256d half = _mm256_set1_pd(0.5), hundredth = _mm256_set1_pd(0.01);
  const __m128i lo = _mm256_cvttpd_epi32(
      _mm256_mul_pd(_mm256_add_pd(_mm256_cvtepi32_pd(_mm256_castsi256_si128(n)), half), hundredth));
  const __m128i hi = _mm256_cvttpd_epi32(_mm256_mul_pd(
      _mm256_add_pd(_mm256_cvtepi32_pd(_mm256_extracti128_si256(n, 1)), half), hundredth));
  return _mm256_set_m128i(hi, lo);
}

// The same for 0 <= n < 2^23, in float: n + 0.5 is exact, and the
// correctly rounded quotient (< 2^17, so within 2^-8 of (n + 0.5) / 100)
// truncates to floor(n / 100). One vdivps for 8 lanes, against
// divideBy100's two halves in double (6 fewer instructions a vector).
HOROPTER_AVX2_TARGET inline __m256i divideBy100Below2Pow23(__m256i n) {
  return _mm256_cvttps_epi32(_mm256_div_ps(
      _mm256_add_ps(_mm256_cvtepi32_ps(n), _mm256_set1_ps(0.5f)), _mm256_set1_ps(100.0f)));
}

// b where mask, else a, for a mask of whole 16-bit lanes (all ones or
// zeros): vpblendvb. Written as asm because GCC 12 folds
// _mm256_blendv_epi8 into a select on "mask < 0" per byte and emits that
// as a byte compare (vpcmpgtb) plus the blend: one more instruction per
// merge in the winner searches (4 M per 1280x720 frame at 128 disparities).
[[gnu::always_inline]] HOROPTER_AVX2_TARGET inline __m256i blendWords(__m256i a, __m256i b,
                                                                      __m256i mask) {
  // The result in a's register: the accumulators are blended in place.
  asm("vpblendvb %2, %1, %0, %0" : "+x"(a) : "xm"(b), "x"(mask));
  return a;
}

// The least key over lanes k = 0 .. count - 1 (lane k's 16 entries at
// c + k * step), for kBlocks (4) blocks of 16 consecutive entries, and
// index[j] (a vector) of the group j that holds it. With G = 2^kShift and
// Q = count / G, group j is the lanes j + qQ, q = 0 .. G - 1, whose keys
// carry q in their low bits (G * cost + q): the least key of a group is
// its least (cost, q), i.e. the least cost at its smallest k. The groups go
// in increasing j, and a later one wins only with a strictly smaller key:
// over (cost, q, j) that is the least (cost, k), as k = qQ + j with j < Q.
// (Groups of G consecutive lanes, keys k mod G, needed the best key's low
// bits cleared before each compare: 4 instructions per merge, now 3.) The
// caller adds Q times the key's low bits to the index.
template <int kShift, int kBlocks>
[[gnu::always_inline]] HOROPTER_AVX2_TARGET inline void leastKeys(const std::int16_t* c,
                                                                  std::ptrdiff_t step, int count,
                                                                  const std::int16_t* indexOf,
                                                                  __m256i* best, __m256i* index) {
  constexpr int kGroup = 1 << kShift;
  const int groups = count >> kShift;
  const std::ptrdiff_t groupStep = groups * step;
  const auto groupMin = [&](const std::int16_t* p) HOROPTER_AVX2_TARGET {
    __m256i m = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p));
    for (int q = 1; q < kGroup; ++q)
      m = _mm256_min_epi16(m,
                           _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p + q * groupStep)));
    return m;
  };
  // As asm: from intrinsics GCC took the min first, over the best key's
  // register, and copied the best key for the compare (4 instructions).
  const auto merge = [&](__m256i& bestN, __m256i& indexN, __m256i now, __m256i indexK)
                         HOROPTER_AVX2_TARGET {
                           __m256i better;
                           asm("vpcmpgtw %[now], %[best], %[better]\n\t"
                               "vpminsw %[now], %[best], %[best]\n\t"
                               "vpblendvb %[better], %[indexK], %[index], %[index]"
                               : [better] "=&x"(better), [best] "+x"(bestN), [index] "+x"(indexN)
                               : [now] "x"(now), [indexK] "xm"(indexK));
                         };
  // Named accumulators, not arrays: with arrays GCC copies every one at
  // every step. They start above every key ("no cost" keeps the first
  // group's index), so that every group is merged the same way.
  static_assert(kBlocks == 4);
  __m256i best0 = _mm256_set1_epi16(kNoCost), best1 = best0, best2 = best0, best3 = best0;
  __m256i index0 = load(indexOf), index1 = index0, index2 = index0, index3 = index0;
  const auto mergeGroup = [&](int j) HOROPTER_AVX2_TARGET {
    const __m256i indexK = load(indexOf + j * kLanes);
    const std::int16_t* p = c + j * step;
    merge(best0, index0, groupMin(p), indexK);
    merge(best1, index1, groupMin(p + kLanes), indexK);
    merge(best2, index2, groupMin(p + 2 * kLanes), indexK);
    merge(best3, index3, groupMin(p + 3 * kLanes), indexK);
  };
  // Two groups per iteration (count / G is even: count is a multiple of
  // 16, G at most 8): the loop's own 4 instructions were an eighth of what
  // a group took.
  for (int j = 0; j < groups; j += 2) {
    mergeGroup(j);
    mergeGroup(j + 1);
  }
  best[0] = best0;
  best[1] = best1;
  best[2] = best2;
  best[3] = best3;
  index[0] = index0;
  index[1] = index1;
  index[2] = index2;
  index[3] = index3;
}

// The uniqueness limit's floor(c * r / 100) as floor(c * M / 2^s) (one
// vpmulhuw, high 16 bits, and a shift by s - 16): s is the largest in
// [16, 31] with M = ceil(2^s r / 100) <= 65535 (0: none, r >= 100). With
// e = 100 M - 2^s r >= 0 and c r = 100 q + f, c M / 2^s = q + (f +
// c e / 2^s) / 100, and f is a multiple of g = gcd(r, 100), at most
// 100 - g: the floor is q for every c <= bound iff bound * e < g * 2^s
// suffices, which limitMultiplier checks (M, or 0 where it fails: the
// limit is then computed in 32 bits).
inline int limitShiftFor(int r) {
  int s = 0;
  for (int t = 16; t < 32 && r > 0; ++t)
    if (((std::int64_t{1} << t) * r + 99) / 100 <= 0xFFFF) s = t;
  return s;
}
inline int limitMultiplier(int r, std::int64_t bound) {
  const int s = limitShiftFor(r);
  if (s == 0 || bound > 0xFFFF) return 0;
  const std::int64_t scale = std::int64_t{1} << s;
  const std::int64_t m = (scale * r + 99) / 100;
  const std::int64_t e = 100 * m - scale * r;
  return bound * e < std::gcd(r, 100) * scale ? static_cast<int>(m) : 0;
}

// Entries per row of costs for at least n (a multiple of 16): the least
// count >= n that is 32 more than a multiple of 64, i.e. an odd number of
// 64-byte lines. The decisions read the rows of all lanes together, a few
// lines of each; rows a multiple of 2 lines apart fall in fewer of the L1
// cache's 64 sets (1536 entries, 3 KB, at 1280 pixels and 128 disparities:
// 4 set offsets, 16 sets for a tile's 4 lines per row), and the 128 rows
// evicted each other (D1 read misses: 41 % of decideLeft's reads). With an
// odd number of lines, 64 consecutive rows start in 64 different sets.
constexpr int rowEntries(int n) {
  return n + (96 - n % 64) % 64;
}

// The 16-lane groups a guard of step 1 or 2 adds to the sweep below the
// range's: every disparity of its span, those it does not check masked.
// 0 without a guard, or with a larger step, whose checked disparities get
// separate sums (about 1.5 M instructions each on a 640x480 frame at block
// 9, against 0.32 M per disparity swept).
inline int foldedGuardGroups(const StereoParams& params, const BelowRangeGuard& guard) {
  return guard.step == 1 || guard.step == 2
             ? (guardCount(params, guard) * guard.step + kLanes - 1) / kLanes
             : 0;
}

class Matcher {
  // decideLeft and decideRight take 4 blocks of 16 pixels per pass.
  static constexpr int kChunk = 4 * kLanes;
  // Pixels per tile of a row pass (a multiple of kChunk).
  static constexpr int kTile = 2 * kChunk;
  // Pixels each pair of groups sweeps ahead of the pair below it (a
  // multiple of 16). Right pixel xr reads lane k at left pixel xr + k, so
  // with every lane swept tile by tile a block's candidates were written
  // over 64 + 127 pixels at 128 lanes (about 97 KB of costs and column sums,
  // three times L1) and half of decideRight's reads missed it. With pair p
  // 32 p pixels ahead, lane k's costs at pixel x are written at about sweep
  // position x - k, so a block's candidates come from the last 64 + 31
  // pixels swept; the left decisions, which read every lane of a pixel,
  // reach back as far in turn. 1280x720/d128/w15, one thread: ratio to
  // cv::StereoBM 3.22 -> 3.35 (kernels/README.md); 16, 48 and 64 gained less.
  static constexpr int kPairLead = 32;
  // numDisparities <= 1024, and as many below the range for a folded guard.
  static constexpr int kMaxGroups = 2048 / kLanes;

 public:
  HOROPTER_AVX2_TARGET Matcher(const ConstImageView& left, const ConstImageView& right,
                               const ConstImageView& texture, const StereoParams& params,
                               const BelowRangeGuard& guard, const ImageView& disparity,
                               const ImageView& winnerRight, const MatchRegion& region,
                               int keyShift, bool narrow, bool smallProducts, int costBound)
      : left_(left),
        right_(right),
        texture_(texture),
        params_(params),
        disparity_(disparity),
        winnerRight_(winnerRight),
        width_(left.width),
        r_(params.blockSize / 2),
        count_(params.numDisparities),
        groups_(params.numDisparities / kLanes),
        minD_(params.minDisparity),
        guardGroups_(foldedGuardGroups(params, guard)),
        sweepGroups_(groups_ + guardGroups_),
        sweepMin_(minD_ - guardGroups_ * kLanes),
        x0_(region.x0),
        x1_(region.x1),
        xa_(region.x0 - r_),
        xb_(region.x1 + r_),
        cols_(xb_ - xa_ + 1),
        pixels_(region.x1 - region.x0),
        padded_((pixels_ + kChunk - 1) / kChunk * kChunk),
        edge_(count_ + guardGroups_ * kLanes + kChunk),
        rowLen_(rowEntries(padded_ + 2 * edge_)),
        useTexture_(params.textureThreshold > 0),
        keyShift_(keyShift),
        narrow_(narrow),
        smallProducts_(smallProducts),
        limitMultiplier_(limitMultiplier(params.uniquenessRatio, costBound)),
        limitShift_(limitMultiplier_ > 0 ? limitShiftFor(params.uniquenessRatio) - 16 : 0),
        keyInit_(static_cast<std::size_t>(sweepGroups_) * kLanes),
        columnSum_(static_cast<std::size_t>(sweepGroups_) * cols_ * kLanes),
        columnTexture_(cols_ + kLanes),
        texturePrefix_(cols_ + kLanes),
        leftPairs_(cols_),
        rightPairs_(2 * static_cast<std::size_t>(width_ + guardGroups_ * kLanes)),
        reversedIn_(width_ + guardGroups_ * kLanes),
        reversedOut_(width_ + guardGroups_ * kLanes),
        // Rows -1 and count, the edges and the columns past the last pixel
        // hold "no cost": never a winner, never within a uniqueness limit
        // (< 65535). Filled once, not zeroed first (400 KB at 1280x720
        // and 128 disparities, written twice per call).
        costs_(static_cast<std::size_t>(costRows()) * rowLen_, kNoCost),
        laneOf_(static_cast<std::size_t>(count_) * kLanes),
        disparityOf_(static_cast<std::size_t>(count_) * kLanes),
        pxTexture_(padded_),
        guardStep_(guard.step),
        guards_(guardCount(params, guard)),
        guardStride_((cols_ + 2 * kChunk) / kLanes * kLanes),
        guardColumns_(static_cast<std::size_t>(guardGroups_ > 0 ? 0 : guards_) * guardStride_),
        guardLeast_(guards_ > 0 ? padded_ + kLanes : 0),
        guardEdge_((minD_ + count_ - 1 - guard.lowest + 2 * kLanes) / kLanes * kLanes),
        guardRowLen_(guardEdge_ + padded_ + kChunk + 2 * kLanes),
        guardCosts_(static_cast<std::size_t>(guardGroups_ > 0 ? 0 : guards_) * guardRowLen_),
        guardDisparityOf_(static_cast<std::size_t>(guardGroups_) * kLanes * kLanes),
        laneZero_(costs_.get() + static_cast<std::size_t>(1 + guardGroups_ * kLanes) * rowLen_ +
                  edge_) {
    std::fill_n(guardCosts_.get(),
                static_cast<std::size_t>(guardGroups_ > 0 ? 0 : guards_) * guardRowLen_,
                std::uint16_t{0xFFFF});
    for (int k = 0; k < guardGroups_ * kLanes; ++k)
      std::fill_n(guardDisparityOf_.get() + k * kLanes, kLanes,
                  static_cast<std::int16_t>(sweepMin_ + k));
    for (int k = -guardGroups_ * kLanes; k < 0; ++k)
      guardNoCostLeast_ = std::min(guardNoCostLeast_, guardNoCostFrom(k));
    // Each lane's key bits: k / (count / G) over the range's lanes, the
    // same over a folded guard's below them (see leastKeys).
    const int guardLanes = guardGroups_ * kLanes;
    for (int k = -guardLanes; k < count_; ++k) {
      const int bits =
          k < 0 ? (k + guardLanes) / (guardLanes >> keyShift) : k / (count_ >> keyShift);
      keyInit_.get()[k + guardLanes] = static_cast<std::int16_t>(kBias + bits);
    }
    for (int k = 0; k < count_; ++k) {
      std::fill_n(laneOf_.get() + k * kLanes, kLanes, static_cast<std::int16_t>(k));
      std::fill_n(disparityOf_.get() + k * kLanes, kLanes, static_cast<std::int16_t>(minD_ + k));
    }
  }

  // Asks run() to keep, per row y and right pixel xr in [0, end), the least
  // cost over the region's candidates (65535: none) at least[(y - y0) *
  // stride + xr], for the left band's pass (stride >= end + kChunk).
  void exportRightLeast(std::uint16_t* least, std::ptrdiff_t stride, int end, int y0) {
    rightLeast_ = least;
    rightLeastStride_ = stride;
    rightLeastEnd_ = end;
    rightLeastY0_ = y0;
  }

  HOROPTER_AVX2_TARGET void run(int y0, int y1) {
    const bool separateGuard = guards_ > 0 && guardGroups_ == 0;
    for (int j = y0 - r_; j <= y0 + r_; ++j) {
      if (j < y0 + r_) {
        accumulateTwoRows(j);
        if (separateGuard) accumulateGuardRow(j);
        ++j;
      } else {
        accumulateRow(j);
      }
      if (separateGuard) accumulateGuardRow(j);
    }
    if (separateGuard) guardRow();
    rowPass<false>(y0);
    for (int y = y0 + 1; y < y1; ++y) {
      reverseRow(right_.row<std::uint8_t>(y + r_), width_, reversedIn());
      reverseRow(right_.row<std::uint8_t>(y - r_ - 1), width_, reversedOut());
      if (useTexture_) slideTexture(y + r_, y - r_ - 1);
      if (separateGuard) {
        slideGuard(y + r_, y - r_ - 1);
        guardRow();
      }
      rowPass<true>(y);
    }
  }

 private:
  // Column sums of group g (lanes d = minD + 16g ..), column x.
  HOROPTER_AVX2_TARGET std::int16_t* column(int g, int x) const {
    return columnSum_.get() + (static_cast<std::size_t>(g) * cols_ + (x - xa_ + 1)) * kLanes;
  }
  HOROPTER_AVX2_TARGET std::uint16_t* columnTexture(int x) const {
    return columnTexture_.get() + (x - xa_ + 1);
  }
  // Offset in a reversed right row of the sweep's first disparity (sweepMin)
  // for left column x. A folded guard's lanes read up to 16 * guardGroups
  // bytes before the row (x - d past the image's right edge: their costs
  // there are replaced by "no cost", fixGuardTile), which the arrays hold.
  HOROPTER_AVX2_TARGET int reversedBase(int x) const { return width_ - 1 - x + sweepMin_; }
  HOROPTER_AVX2_TARGET std::uint8_t* reversedIn() const {
    return reversedIn_.get() + guardGroups_ * kLanes;
  }
  HOROPTER_AVX2_TARGET std::uint8_t* reversedOut() const {
    return reversedOut_.get() + guardGroups_ * kLanes;
  }
  // Rows of costs: lanes -16 * guardGroups .. count - 1 (a folded guard's
  // below lane 0), with one row of "no cost" below and above.
  HOROPTER_AVX2_TARGET int costRows() const { return count_ + guardGroups_ * kLanes + 2; }
  // Window costs of lane k (-16 * guardGroups - 1 ..= count) for pixels
  // i = x - x0 from 0, biased.
  HOROPTER_AVX2_TARGET std::int16_t* costs(int k) const {
    return laneZero_ + static_cast<std::ptrdiff_t>(k) * rowLen_;
  }

  // Adds rows j and j + 1 to the column sums (and to the texture sums), as
  // the sweep slides them: both rows' bytes interleaved, |L - R| of both in
  // one byte vector per 16 lanes, and maddubs with (G, G) makes G times
  // their sum. 10 instructions per column and pair of groups for two rows,
  // where accumulateRow takes 18 for one (1.25 M instructions for the 15
  // rows of a 1280x720 call at 128 disparities).
  HOROPTER_AVX2_TARGET void accumulateTwoRows(int j) {
    const auto* l0 = left_.row<std::uint8_t>(j);
    const auto* l1 = left_.row<std::uint8_t>(j + 1);
    reverseRow(right_.row<std::uint8_t>(j), width_, reversedIn());
    reverseRow(right_.row<std::uint8_t>(j + 1), width_, reversedOut());
    interleaveBytes(l0 + xa_, l1 + xa_, xb_ - xa_,
                    reinterpret_cast<std::uint8_t*>(leftPairs_.get()));
    interleaveBytes(reversedIn_.get(), reversedOut_.get(), width_ + guardGroups_ * kLanes,
                    rightPairs_.get());
    const int unit = 1 << keyShift_;
    const __m256i units = _mm256_set1_epi16(static_cast<std::int16_t>(unit << 8 | unit));
    const auto addBoth = [&](std::int16_t* col, __m256i l,
                             const std::uint8_t* r) HOROPTER_AVX2_TARGET {
      const __m256i ad = narrow_ ? absDiffRows<true>(l, loadu(r)) : absDiffRows<false>(l, loadu(r));
      store(col, _mm256_add_epi16(load(col), _mm256_maddubs_epi16(ad, units)));
    };
    const int pairs = sweepGroups_ / 2;
    const std::int16_t* li = leftPairs_.get();
    for (int x = xa_; x < xb_; ++x, ++li) {
      const __m256i l = _mm256_set1_epi16(*li);
      const std::uint8_t* ri = rightPairs_.get() + 2 * (guardGroups_ * kLanes + reversedBase(x));
      for (int p = 0; p < pairs; ++p) {
        addBoth(column(2 * p, x), l, ri + p * 4 * kLanes);
        addBoth(column(2 * p + 1, x), l, ri + p * 4 * kLanes + 2 * kLanes);
      }
      if (sweepGroups_ % 2 != 0)
        addBoth(column(sweepGroups_ - 1, x), l, ri + (sweepGroups_ - 1) * 2 * kLanes);
    }
    if (useTexture_) {
      const auto* t0 = texture_.row<std::uint8_t>(j);
      const auto* t1 = texture_.row<std::uint8_t>(j + 1);
      for (int x = xa_; x < xb_; ++x)
        *columnTexture(x) = static_cast<std::uint16_t>(*columnTexture(x) + t0[x] + t1[x]);
    }
  }

  // Adds row j's |L - R| to every column sum (and T to the texture sums).
  HOROPTER_AVX2_TARGET void accumulateRow(int j) {
    const auto* l = left_.row<std::uint8_t>(j);
    reverseRow(right_.row<std::uint8_t>(j), width_, reversedIn());
    const int pairs = sweepGroups_ / 2;
    const __m128i shift = _mm_cvtsi32_si128(keyShift_);
    for (int x = xa_; x < xb_; ++x) {
      const __m256i l8 = _mm256_set1_epi8(static_cast<char>(l[x]));
      const std::uint8_t* rv = reversedIn() + reversedBase(x);
      for (int p = 0; p < pairs; ++p) {
        const __m256i ad = absDiff8(l8, loadu(rv + p * 2 * kLanes));
        std::int16_t* colA = column(2 * p, x);
        std::int16_t* colB = column(2 * p + 1, x);
        const __m256i adA =
            _mm256_sll_epi16(_mm256_cvtepu8_epi16(_mm256_castsi256_si128(ad)), shift);
        const __m256i adB =
            _mm256_sll_epi16(_mm256_cvtepu8_epi16(_mm256_extracti128_si256(ad, 1)), shift);
        store(colA, _mm256_add_epi16(load(colA), adA));
        store(colB, _mm256_add_epi16(load(colB), adB));
      }
    }
    for (int x = xa_; x < xb_; ++x) {
      const __m256i lv = _mm256_set1_epi16(l[x]);
      const std::uint8_t* rv = reversedIn() + reversedBase(x);
      for (int g = 2 * pairs; g < sweepGroups_; ++g) {
        std::int16_t* col = column(g, x);
        const __m256i ad = _mm256_abs_epi16(_mm256_sub_epi16(lv, widen(rv + g * kLanes)));
        store(col, _mm256_add_epi16(load(col), _mm256_sll_epi16(ad, shift)));
      }
    }
    if (useTexture_) {
      const auto* t = texture_.row<std::uint8_t>(j);
      for (int x = xa_; x < xb_; ++x)
        *columnTexture(x) = static_cast<std::uint16_t>(*columnTexture(x) + t[x]);
    }
  }

  // Texture column sums: add row `in`, drop row `out`.
  HOROPTER_AVX2_TARGET void slideTexture(int in, int out) {
    const auto* tIn = texture_.row<std::uint8_t>(in);
    const auto* tOut = texture_.row<std::uint8_t>(out);
    int x = xa_;
    for (; x + 16 <= xb_; x += 16) {
      auto* p = reinterpret_cast<__m256i*>(columnTexture(x));
      const __m256i sum = _mm256_add_epi16(_mm256_loadu_si256(p), widen(tIn + x));
      _mm256_storeu_si256(p, _mm256_sub_epi16(sum, widen(tOut + x)));
    }
    for (; x < xb_; ++x)
      *columnTexture(x) = static_cast<std::uint16_t>(*columnTexture(x) + tIn[x] - tOut[x]);
  }

  // Every pixel's texture window sum, pxTexture_[i] = t[i] + .. + t[i + 2r]
  // (t: the column sums from column xa), as P[i + 2r + 1] - P[i] of the
  // prefix sums P[j] = t[0] + .. + t[j - 1], 8 per vector: a scan within
  // 128-bit lanes, the low lane's total carried into the high one, and the
  // previous vector's last sum added. (One pixel at a time it took 10
  // instructions a pixel, 8 M per 1280x720 frame.) Sums are exact in 32
  // bits; the prefix may wrap, the differences do not.
  HOROPTER_AVX2_TARGET void textureSums() {
    const std::uint16_t* t = columnTexture(xa_);
    int* prefix = texturePrefix_.get();  // P[0] stays 0
    const int columns = xb_ - xa_;
    const __m256i last = _mm256_set1_epi32(7);
    __m256i carry = _mm256_setzero_si256();
    for (int j = 0; j < columns; j += 8) {  // reads up to 7 zero columns past the end
      __m256i x = _mm256_cvtepu16_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(t + j)));
      x = _mm256_add_epi32(x, _mm256_slli_si256(x, 4));
      x = _mm256_add_epi32(x, _mm256_slli_si256(x, 8));
      const __m256i lowTotal = _mm256_shuffle_epi32(x, 0xFF);
      x = _mm256_add_epi32(x, _mm256_permute2x128_si256(lowTotal, lowTotal, 0x08));
      x = _mm256_add_epi32(x, carry);
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(prefix + 1 + j), x);
      carry = _mm256_permutevar8x32_epi32(x, last);
    }
    const int window = 2 * r_ + 1;
    int* sums = pxTexture_.get();
    for (int i = 0; i < pixels_; i += 8) {  // up to 7 lanes past the last pixel: unused
      const __m256i sum = _mm256_sub_epi32(load8x32(prefix + i + window), load8x32(prefix + i));
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(sums + i), sum);
    }
  }

  // The guard's checked disparity n (0 .. guards - 1), the end of the
  // columns whose right pixel lies inside the image (x - g < W), and the end
  // of the pixels i = x - x0 where it counts (x < W - r + g).
  HOROPTER_AVX2_TARGET int guardDisparity(int n) const { return minD_ - (n + 1) * guardStep_; }
  HOROPTER_AVX2_TARGET int guardColumnEnd(int n) const {
    return std::min(xb_, width_ + guardDisparity(n));
  }
  HOROPTER_AVX2_TARGET int guardPixelEnd(int n) const {
    return std::min(x1_, width_ - r_ + guardDisparity(n)) - x0_;
  }
  // Window costs of checked disparity n for pixels i = x - x0 (65535 where
  // it does not count); entries from -guardEdge_.
  HOROPTER_AVX2_TARGET std::uint16_t* guardCosts(int n) const {
    return guardCosts_.get() + static_cast<std::size_t>(n) * guardRowLen_ + guardEdge_;
  }
  // Column sums of checked disparity n, entry x - xa (zero past the end).
  HOROPTER_AVX2_TARGET std::uint16_t* guardColumn(int n) const {
    return guardColumns_.get() + static_cast<std::size_t>(n) * guardStride_;
  }

  // Adds row j's |L - R| at every checked disparity to its column sums.
  HOROPTER_AVX2_TARGET void accumulateGuardRow(int j) {
    const auto* l = left_.row<std::uint8_t>(j);
    const auto* rr = right_.row<std::uint8_t>(j);
    for (int n = 0; n < guards_; ++n) {
      const int g = guardDisparity(n);
      std::uint16_t* col = guardColumn(n);
      for (int x = xa_; x < guardColumnEnd(n); ++x)
        col[x - xa_] = static_cast<std::uint16_t>(col[x - xa_] + std::abs(l[x] - rr[x - g]));
    }
  }

  // The guard's column sums: add row `in`, drop row `out`.
  HOROPTER_AVX2_TARGET void slideGuard(int in, int out) {
    const auto* lIn = left_.row<std::uint8_t>(in);
    const auto* lOut = left_.row<std::uint8_t>(out);
    const auto* rIn = right_.row<std::uint8_t>(in);
    const auto* rOut = right_.row<std::uint8_t>(out);
    const auto absDiff16 = [&](const std::uint8_t* a, const std::uint8_t* b) HOROPTER_AVX2_TARGET {
      const __m128i va = loadu128(a), vb = loadu128(b);
      return _mm256_cvtepu8_epi16(_mm_or_si128(_mm_subs_epu8(va, vb), _mm_subs_epu8(vb, va)));
    };
    for (int n = 0; n < guards_; ++n) {
      const int g = guardDisparity(n), end = guardColumnEnd(n);
      std::uint16_t* col = guardColumn(n) - xa_;  // col[x]
      int x = xa_;
      for (; x + kLanes <= end; x += kLanes) {
        auto* p = reinterpret_cast<__m256i*>(col + x);
        const __m256i sum =
            _mm256_add_epi16(_mm256_loadu_si256(p), absDiff16(lIn + x, rIn + (x - g)));
        _mm256_storeu_si256(p, _mm256_sub_epi16(sum, absDiff16(lOut + x, rOut + (x - g))));
      }
      for (; x < end; ++x)
        col[x] = static_cast<std::uint16_t>(col[x] + std::abs(lIn[x] - rIn[x - g]) -
                                            std::abs(lOut[x] - rOut[x - g]));
    }
  }

  // A folded guard's lanes (k < 0) after the sweep of pixels [i0, i1):
  // "no cost" in the lanes it does not check (below `lowest`, in a partial
  // group, or between the checked ones with step 2) and at the pixels where a checked one does not
  // count (its window reaches past the right image: x >= W - r + d, read from the reversed rows'
  // padding), so that decideRight's candidates are only those that count; then their least cost per
  // pixel, for finishLeft (65535: none).
  HOROPTER_AVX2_TARGET void fixGuardTile(int i0, int i1) {
    // Whole passes of 4 blocks (past the last pixel the rows hold "no cost").
    const int end = std::min((i1 + kChunk - 1) / kChunk * kChunk, padded_);
    for (int k = -guardGroups_ * kLanes; k < 0 && end > guardNoCostLeast_; ++k) {
      const int from = std::clamp(guardNoCostFrom(k), i0, end);
      if (from < end) std::fill(costs(k) + from, costs(k) + end, kNoCost);
    }
    const __m256i bias16 = _mm256_set1_epi16(static_cast<std::int16_t>(kBias));
    const __m256i ones = _mm256_set1_epi16(-1);
    const __m128i shift = _mm_cvtsi32_si128(keyShift_);
    const std::ptrdiff_t rowLen = rowLen_;
    for (int b = i0; b < end; b += kChunk) {
      static_assert(kChunk == 4 * kLanes);
      __m256i l0 = _mm256_set1_epi16(kNoCost), l1 = l0, l2 = l0, l3 = l0;
      const std::int16_t* c = costs(-guards_ * guardStep_) + b;
      for (int k = 0; k < guards_; ++k, c += guardStep_ * rowLen) {
        l0 = _mm256_min_epi16(l0, load(c));
        l1 = _mm256_min_epi16(l1, load(c + kLanes));
        l2 = _mm256_min_epi16(l2, load(c + 2 * kLanes));
        l3 = _mm256_min_epi16(l3, load(c + 3 * kLanes));
      }
      const __m256i least[4] = {l0, l1, l2, l3};
      for (int n = 0; n < 4; ++n) {
        const __m256i key = _mm256_xor_si256(least[n], bias16);
        _mm256_storeu_si256(
            reinterpret_cast<__m256i*>(guardLeast_.get() + b + kLanes * n),
            _mm256_or_si256(_mm256_srl_epi16(key, shift), _mm256_cmpeq_epi16(key, ones)));
      }
    }
  }
  // The first pixel from which a folded guard's lane k (< 0, disparity
  // minD + k) holds "no cost": 0 where it is not checked, else where it
  // stops counting.
  HOROPTER_AVX2_TARGET int guardNoCostFrom(int k) const {
    const bool checked = -k % guardStep_ == 0 && -k / guardStep_ <= guards_;
    return checked ? std::max(0, guardPixelEnd(-k / guardStep_ - 1)) : 0;
  }

  // The current row's window costs of every checked disparity, and their
  // least per pixel i (65535 where none counts): pixel i's window is columns
  // x0 + i - r .. x0 + i + r, entries i .. i + 2r of a guard column.
  HOROPTER_AVX2_TARGET void guardRow() {
    std::uint16_t* least = guardLeast_.get();
    std::fill_n(least, padded_ + kLanes, std::uint16_t{0xFFFF});
    const int window = 2 * r_ + 1;
    for (int n = 0; n < guards_; ++n) {
      const std::uint16_t* col = guardColumn(n);
      std::uint16_t* out = guardCosts(n);
      const int end = guardPixelEnd(n);
      for (int i = 0; i < end; i += kLanes) {
        __m256i sum = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(col + i));
        for (int c = 1; c < window; ++c)
          sum = _mm256_add_epi16(sum,
                                 _mm256_loadu_si256(reinterpret_cast<const __m256i*>(col + i + c)));
        auto* p = reinterpret_cast<__m256i*>(least + i);
        if (i + kLanes <= end) {
          _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + i), sum);
          _mm256_storeu_si256(p, _mm256_min_epu16(_mm256_loadu_si256(p), sum));
        } else {
          alignas(32) std::uint16_t lanes[kLanes];
          _mm256_store_si256(reinterpret_cast<__m256i*>(lanes), sum);
          for (int j = 0; i + j < end; ++j) {
            out[i + j] = lanes[j];
            least[i + j] = std::min(least[i + j], lanes[j]);
          }
        }
      }
    }
  }

  // Sweep state of one group pair (or of the last, unpaired group): where
  // the next pixel's column sums, dropped columns and input bytes lie, and
  // the running window costs.
  struct SweepState {
    std::int16_t* colA;
    std::int16_t* colB;
    const std::int16_t* dropA;
    const std::int16_t* dropB;
    const std::uint8_t* ri;  // rightPairs_: (in, out) bytes of lane 0's right pixel
    const std::uint8_t* li;  // leftPairs_: (in, out) bytes of the left pixel
    __m256i costA, costB;
  };

  // One row, tile by tile (kTile pixels): the sweep of every group over the
  // tile, then its left decisions, then the right winners whose costs are
  // all in; the tile's costs are still in cache when the decisions read them.
  template <bool kSlide>
  HOROPTER_AVX2_TARGET void rowPass(int y) {
    if (rightLeast_ != nullptr)
      rightLeastRow_ = rightLeast_ + (y - rightLeastY0_) * rightLeastStride_;
    const auto* lIn = left_.row<std::uint8_t>(kSlide ? y + r_ : y);
    const auto* lOut = left_.row<std::uint8_t>(kSlide ? y - r_ - 1 : y);
    const int pairs = sweepGroups_ / 2;
    const bool odd = sweepGroups_ % 2 != 0;
    if constexpr (kSlide) {
      // The entering and leaving rows' bytes interleaved, left pixels (one
      // 16-bit word per column, which the sweep broadcasts from memory) and
      // reversed right rows: |L - R| of both rows is then one byte vector
      // per 16 lanes, (in, out) per lane, and maddubs with (G, -G) makes
      // G * (in - out) in natural lane order.
      interleaveBytes(lIn + xa_, lOut + xa_, xb_ - xa_,
                      reinterpret_cast<std::uint8_t*>(leftPairs_.get()));
      interleaveBytes(reversedIn_.get(), reversedOut_.get(), width_ + guardGroups_ * kLanes,
                      rightPairs_.get());
    }
    if (useTexture_) textureSums();

    SweepState state[kMaxGroups / 2 + 1];
    for (int p = 0; p < pairs; ++p) {
      SweepState& s = state[p];
      s.colA = column(2 * p, xa_);
      s.colB = column(2 * p + 1, xa_);
      s.dropA = column(2 * p, xa_ - 1);  // all zeros while warming up
      s.dropB = column(2 * p + 1, xa_ - 1);
      s.ri = rightPairs_.get() + 2 * (guardGroups_ * kLanes + reversedBase(xa_) + p * 2 * kLanes);
      s.li = reinterpret_cast<const std::uint8_t*>(leftPairs_.get());
      s.costA = load(keyInit_.get() + 2 * p * kLanes);
      s.costB = load(keyInit_.get() + (2 * p + 1) * kLanes);
    }
    if (odd) {
      const int g = sweepGroups_ - 1;
      SweepState& s = state[pairs];
      s.colA = column(g, xa_);
      s.dropA = column(g, xa_ - 1);
      s.ri = rightPairs_.get() + 2 * (guardGroups_ * kLanes + reversedBase(xa_) + g * kLanes);
      s.li = reinterpret_cast<const std::uint8_t*>(leftPairs_.get());
      s.costA = load(keyInit_.get() + g * kLanes);
    }

    std::int16_t* outDisparity = disparity_.row<std::int16_t>(y);
    std::int16_t* outWinner = winnerRight_.row<std::int16_t>(y);
    const int xrLow = x0_ - (minD_ + count_ - 1);
    const int xrHigh = x1_ - 1 - minD_;  // inclusive
    int xr0 = xrLow;
    // Pixels each pair's sweep has costed so far (the unpaired group last).
    int swept[kMaxGroups / 2 + 1] = {};
    const int sweeps = pairs + (odd ? 1 : 0);
    const int guardLanes = guardGroups_ * kLanes;
    for (int i0 = 0; i0 < pixels_; i0 += kTile) {
      const int i1 = std::min(i0 + kTile, pixels_);
      // Pair p sweeps up to p * kPairLead pixels past the tile (see
      // kPairLead); the first row (no slide) has no differences of rows.
      const auto sweepAll = [&](auto narrow) HOROPTER_AVX2_TARGET {
        constexpr bool kNarrow = decltype(narrow)::value;
        for (int p = 0; p < sweeps; ++p) {
          const int to = std::min(i1 + p * kPairLead, pixels_);
          if (to <= swept[p]) continue;
          if (p < pairs)
            sweepPair<kSlide, kNarrow>(p, state[p], swept[p], to);
          else
            sweepLast<kSlide, kNarrow>(state[p], swept[p], to);
          swept[p] = to;
        }
      };
      if (kSlide && narrow_)
        sweepAll(std::true_type{});
      else
        sweepAll(std::false_type{});
      // Whether right pixels [xr, xr + kChunk) have every cost they read:
      // lane k of right pixel xr is left pixel xr + minD + k - x0.
      const auto rightReady = [&](int xr) {
        // A folded guard's lanes are final only where fixGuardTile has been.
        if (guardGroups_ > 0 && i1 < pixels_ && xr + kChunk - 1 + minD_ - 1 - x0_ >= i1)
          return false;
        for (int p = 0; p < sweeps; ++p) {
          if (swept[p] >= pixels_) continue;  // past the last pixel: "no cost"
          const int lastLane = std::min(2 * (p + 1), sweepGroups_) * kLanes - 1 - guardLanes;
          if (xr + kChunk - 1 + minD_ + lastLane - x0_ >= swept[p]) return false;
        }
        return true;
      };
      if (guardGroups_ > 0) fixGuardTile(i0, i1);
      const auto decide = [&](auto shift) HOROPTER_AVX2_TARGET {
        constexpr int kShift = decltype(shift)::value;
        decideLeft<kShift>(outDisparity, i0, i1);
        for (; xr0 <= xrHigh; xr0 += kChunk) {
          if (!rightReady(xr0)) break;
          decideRight<kShift>(outWinner, xr0, xrHigh);
        }
      };
      switch (keyShift_) {
        case 0:
          decide(std::integral_constant<int, 0>{});
          break;
        case 1:
          decide(std::integral_constant<int, 1>{});
          break;
        case 2:
          decide(std::integral_constant<int, 2>{});
          break;
        default:
          decide(std::integral_constant<int, 3>{});
          break;
      }
    }
  }

  // The last, unpaired group's sweep over pixels [i0, i1) (from the row's
  // first column when i0 = 0): along x, each column slides down a row
  // (kSlide) and the window cost takes it in and drops column x - 2r - 1;
  // every 16 pixels, their 16 cost vectors are transposed in registers and
  // stored by lane.
  template <bool kSlide, bool kNarrow>
  HOROPTER_AVX2_TARGET void sweepLast(SweepState& s, int i0, int i1) {
    const int g = sweepGroups_ - 1, pixels = pixels_, window = 2 * r_ + 1;
    const std::ptrdiff_t rowLen = rowLen_;
    std::int16_t* col = s.colA;
    const std::int16_t* drop = s.dropA;
    const std::uint8_t* ri = s.ri;  // (in, out) byte pairs of the right pixels
    const auto* li = reinterpret_cast<const std::int16_t*>(s.li);  // (in, out) left bytes
    __m256i cost = s.costA;
    const int unit = 1 << keyShift_;
    const __m256i plusMinus =
        _mm256_set1_epi16(static_cast<std::int16_t>((256 - unit) << 8 | unit));
    // One column: slide it, add it, drop `drop`; on to the next column.
    // |L - R| of both rows in one byte vector, (in, out) per lane, so that
    // maddubs with (G, -G) gives G * (in - out) in natural lane order.
    const auto step = [&](bool moveDrop) HOROPTER_AVX2_TARGET {
      __m256i c = load(col);
      if constexpr (kSlide) {
        const __m256i ad = absDiffRows<kNarrow>(_mm256_set1_epi16(*li), loadu(ri));
        c = _mm256_add_epi16(c, _mm256_maddubs_epi16(ad, plusMinus));
        store(col, c);
      }
      cost = _mm256_add_epi16(cost, _mm256_sub_epi16(c, load(drop)));
      col += kLanes;
      ++li;
      ri -= 2;
      if (moveDrop) drop += kLanes;
      return cost;
    };
    if (i0 == 0) {
      for (int n = 0; n < window - 1; ++n)
        step(false);
    }
    for (int b = i0; b < i1; b += kLanes) {
      __m256i v[kLanes], t[kLanes];
      if (b + kLanes <= pixels) {
#pragma GCC unroll 16
        for (int j = 0; j < kLanes; ++j)
          v[j] = step(true);
      } else {
        for (int j = 0; j < kLanes; ++j)
          v[j] = b + j < pixels ? step(true) : _mm256_set1_epi16(kNoCost);
      }
      transpose16(v, t);
      std::int16_t* row = costs(g * kLanes + sweepMin_ - minD_) + b;
      for (int k = 0; k < kLanes; ++k, row += rowLen)
        store(row, t[k]);
    }
    s.colA = col;
    s.dropA = drop;
    s.ri = ri;
    s.li = reinterpret_cast<const std::uint8_t*>(li);
    s.costA = cost;
  }

  // The sweep of groups 2p and 2p + 1 together over pixels [i0, i1): as
  // sweepLast's, sharing the broadcast left pixels.
  template <bool kSlide, bool kNarrow>
  HOROPTER_AVX2_TARGET void sweepPair(int p, SweepState& s, int i0, int i1) {
    const int pixels = pixels_, window = 2 * r_ + 1;
    const std::ptrdiff_t rowLen = rowLen_;
    std::int16_t* colA = s.colA;
    std::int16_t* colB = s.colB;
    const std::int16_t* dropA = s.dropA;
    const std::int16_t* dropB = s.dropB;
    const std::uint8_t* ri = s.ri;  // (in, out) byte pairs of the right pixels
    const auto* li = reinterpret_cast<const std::int16_t*>(s.li);  // (in, out) left bytes
    // (in, out) byte pairs times (G, -G): G * (in - out) in 16 bits.
    const int unit = 1 << keyShift_;
    const __m256i plusMinus =
        _mm256_set1_epi16(static_cast<std::int16_t>((256 - unit) << 8 | unit));
    __m256i costA = s.costA;
    __m256i costB = s.costB;
    const auto step = [&](bool moveDrop) HOROPTER_AVX2_TARGET {
      __m256i cA = load(colA), cB = load(colB);
      if constexpr (kSlide) {
        const __m256i l = _mm256_set1_epi16(*li);
        cA = _mm256_add_epi16(cA,
                              _mm256_maddubs_epi16(absDiffRows<kNarrow>(l, loadu(ri)), plusMinus));
        cB = _mm256_add_epi16(
            cB, _mm256_maddubs_epi16(absDiffRows<kNarrow>(l, loadu(ri + 2 * kLanes)), plusMinus));
        store(colA, cA);
        store(colB, cB);
      }
      costA = _mm256_add_epi16(costA, _mm256_sub_epi16(cA, load(dropA)));
      costB = _mm256_add_epi16(costB, _mm256_sub_epi16(cB, load(dropB)));
      colA += kLanes;
      colB += kLanes;
      ++li;
      ri -= 2;
      if (moveDrop) {
        dropA += kLanes;
        dropB += kLanes;
      }
    };
    if (i0 == 0) {
      for (int n = 0; n < window - 1; ++n)
        step(false);
    }
    std::int16_t* const base = costs(p * 2 * kLanes + sweepMin_ - minD_);
    // Half blocks of 8 pixels: each group's 8 cost vectors are transposed
    // within 128-bit lanes and stored as halves (transpose8x16), one group
    // after the other, so that 8 cost vectors, not 16, are live (no spills)
    // and no lane exchange is needed.
    constexpr int kHalf = kLanes / 2;
    int b = i0;
    // Whole half blocks: past the warm-up the dropped column is always
    // `window` columns behind, and group B's column sums a fixed distance
    // after group A's, so one pointer addresses all four (the offsets
    // hidden from the optimizer, which would otherwise keep a pointer for
    // each and add to all of them at every step).
    if (const int whole = (std::min(i1, pixels) - i0) / kHalf; whole > 0) {
      // In bytes: an index register as it is.
      std::ptrdiff_t toB = (colB - colA) * 2, toDrop = (dropA - colA) * 2;
      const auto at = [](std::int16_t* q, std::ptrdiff_t bytes) HOROPTER_AVX2_TARGET {
        return reinterpret_cast<std::int16_t*>(reinterpret_cast<char*>(q) + bytes);
      };
      std::int16_t* out = base + b;
      const std::int16_t* const liEnd = li + whole * kHalf;
      // One group's step at pixel j of the half block from col.
      const auto stepOne = [&](std::int16_t* col, int j, int riOffset,
                               __m256i& cost) HOROPTER_AVX2_TARGET {
        __m256i c = load(col + j * kLanes);
        if constexpr (kSlide) {
          const __m256i l = _mm256_set1_epi16(li[j]);
          c = _mm256_add_epi16(
              c, _mm256_maddubs_epi16(absDiffRows<kNarrow>(l, loadu(ri + riOffset - 2 * j)),
                                      plusMinus));
          store(col + j * kLanes, c);
        }
        cost = _mm256_add_epi16(cost, _mm256_sub_epi16(c, load(at(col + j * kLanes, toDrop))));
        return cost;
      };
      do {
        // In the loop, so that the sums of offsets and constants are not
        // hoisted out of it either.
        asm("" : "+r"(toB), "+r"(toDrop));
        __m256i v[kHalf], t[kHalf];
#pragma GCC unroll 8
        for (int j = 0; j < kHalf; ++j)
          v[j] = stepOne(colA, j, 0, costA);
        transpose8x16(v, t);
        storeHalves(out, rowLen, t);
#pragma GCC unroll 8
        for (int j = 0; j < kHalf; ++j)
          v[j] = stepOne(at(colA, toB), j, 2 * kLanes, costB);
        transpose8x16(v, t);
        storeHalves(out + kLanes * rowLen, rowLen, t);
        colA += kHalf * kLanes;
        li += kHalf;
        ri -= 2 * kHalf;
        out += kHalf;
        asm("" : "+x"(costA), "+x"(costB));
      } while (li != liEnd);
      b += whole * kHalf;
      colB = at(colA, toB);
      dropA = at(colA, toDrop);
      dropB = at(colB, toDrop);
    }
    for (; b < i1; b += kHalf) {
      __m256i v[kHalf], w[kHalf], t[kHalf];
      for (int j = 0; j < kHalf; ++j) {
        if (b + j < pixels) {
          step(true);
          v[j] = costA;
          w[j] = costB;
        } else {
          v[j] = w[j] = _mm256_set1_epi16(kNoCost);
        }
      }
      transpose8x16(v, t);
      storeHalves(base + b, rowLen, t);
      transpose8x16(w, t);
      storeHalves(base + kLanes * rowLen + b, rowLen, t);
    }
    s.colA = colA;
    s.colB = colB;
    s.dropA = dropA;
    s.dropB = dropB;
    s.ri = ri;
    s.li = reinterpret_cast<const std::uint8_t*>(li);
    s.costA = costA;
    s.costB = costB;
  }

  // The left view's decisions of one row, 16 pixels per vector, 64 pixels
  // (4 blocks) per pass over the lanes:
  //   winner: the least key over the lanes (leastKeys), so the first
  //   (smallest d) wins ties; uniqueness: the pixel is valid iff every lane
  //   with cost <= limit is the winner or next to it, i.e. iff the count of
  //   such lanes equals 1 + [C(b - 1) <= limit] + [C(b + 1) <= limit] (rows
  //   -1 and count hold "no cost", above any limit). Then finishLeft, from
  //   the registers. Pixels [from, to): from is a multiple of 64.
  template <int kShift>
  HOROPTER_AVX2_TARGET void decideLeft(std::int16_t* outDisparity, int from, int to) const {
    const int ratio = params_.uniquenessRatio;
    const __m256i keyCap = _mm256_set1_epi16(static_cast<std::int16_t>(0xFFFF >> kShift));
    const __m256i bias16 = _mm256_set1_epi16(static_cast<std::int16_t>(kBias));
    const std::ptrdiff_t rowLen = rowLen_;
    const int count = count_;
    // kBlocks blocks of 16 pixels per pass over the lanes: independent
    // chains, and whole cache lines of each lane's row.
    constexpr int kBlocks = 4;
    const __m256i limitMul = _mm256_set1_epi16(static_cast<std::int16_t>(limitMultiplier_));
    const __m128i limitShift = _mm_cvtsi32_si128(limitShift_);
    // The uniqueness limit least + least * ratio / 100 (integer division)
    // in 32 bits, saturated at 65535: where limitMultiplier finds no exact
    // multiplier.
    const auto limit32 = [&](__m256i least) HOROPTER_AVX2_TARGET {
      const __m256i minLo = _mm256_cvtepu16_epi32(_mm256_castsi256_si128(least));
      const __m256i minHi = _mm256_cvtepu16_epi32(_mm256_extracti128_si256(least, 1));
      const __m256i ratioV = _mm256_set1_epi32(ratio);
      const __m256i productLo = _mm256_mullo_epi32(minLo, ratioV);
      const __m256i productHi = _mm256_mullo_epi32(minHi, ratioV);
      const __m256i limitLo = _mm256_add_epi32(
          minLo, smallProducts_ ? divideBy100Below2Pow23(productLo) : divideBy100(productLo));
      const __m256i limitHi = _mm256_add_epi32(
          minHi, smallProducts_ ? divideBy100Below2Pow23(productHi) : divideBy100(productHi));
      return _mm256_permute4x64_epi64(_mm256_packus_epi32(limitLo, limitHi), 0xD8);
    };
    for (int i0 = from; i0 < to; i0 += kBlocks * kLanes) {
      __m256i best[kBlocks], lane[kBlocks];
      const std::int16_t* c = costs(0) + i0;
      leastKeys<kShift, kBlocks>(c, rowLen, count, laneOf_.get(), best, lane);
      // Per block: one above the largest key of a cost <= limit (G * limit
      // + G, biased; packus saturates at 65535 and the biased add at 0x7FFF,
      // above every real key), and the limit itself saturated at 65535.
      // Unused (zero) when the uniqueness test is off.
      // Not zero-initialised where the test is on: GCC cleared the arrays
      // with two `rep stos` per pass.
      __m256i keyLimit[kBlocks], limit[kBlocks], within[kBlocks];
      for (int n = 0; n < kBlocks && ratio == 0; ++n)
        limit[n] = within[n] = _mm256_setzero_si256();
      for (int n = 0; n < kBlocks && ratio > 0; ++n) {
        const __m256i least = _mm256_srli_epi16(_mm256_xor_si256(best[n], bias16), kShift);
        if (limitMultiplier_ > 0) {
          // least + floor(least * ratio / 100) = least + floor(least * M
          // / 2^s), saturated at 65535 (limitMultiplier).
          limit[n] = _mm256_adds_epu16(
              least, _mm256_srl_epi16(_mm256_mulhi_epu16(least, limitMul), limitShift));
        } else {
          limit[n] = limit32(least);
        }
        // (min(limit, 65535 >> s) << s) + G, saturated at 65535, biased:
        // G * limit + G - 1 + 1, or 0x7FFF where that is 65535 or more.
        keyLimit[n] = _mm256_xor_si256(
            _mm256_adds_epu16(_mm256_slli_epi16(_mm256_min_epu16(limit[n], keyCap), kShift),
                              _mm256_set1_epi16(1 << kShift)),
            bias16);
      }
      if (ratio > 0) {
        // Minus the count of lanes with key < keyLimit[n], i.e. cost <= limit
        // (an add of each -1 mask), in named accumulators: with an array GCC
        // copies every one at every step.
        static_assert(kBlocks == 4);
        c = costs(0) + i0;
        __m256i w0 = _mm256_setzero_si256(), w1 = w0, w2 = w0, w3 = w0;
        // Eight lanes per iteration (count is a multiple of 16), from two
        // pointers 4 rows apart with the stride S and 3S (hidden from GCC,
        // which otherwise keeps 7 offsets, set up again at every pass) as
        // index registers: the loop's own instructions, 4 or 5 per lane
        // when it took one, 6 per 4 lanes after that, are 4 per 8.
        std::ptrdiff_t s = rowLen * 2, s3 = 3 * rowLen * 2;
        asm("" : "+r"(s), "+r"(s3));
        const auto row = [&](const std::int16_t* base, std::ptrdiff_t bytes) HOROPTER_AVX2_TARGET {
          return reinterpret_cast<const std::int16_t*>(reinterpret_cast<const char*>(base) + bytes);
        };
        const std::int16_t* const end = c + count * rowLen;
        do {
          const std::int16_t* c4 = row(c, 4 * s);
          const std::int16_t* const rows[8] = {c,  row(c, s),  row(c, 2 * s),  row(c, s3),
                                               c4, row(c4, s), row(c4, 2 * s), row(c4, s3)};
#pragma GCC unroll 8
          for (int u = 0; u < 8; ++u) {
            const std::int16_t* r = rows[u];
            w0 = _mm256_add_epi16(w0, _mm256_cmpgt_epi16(keyLimit[0], load(r)));
            w1 = _mm256_add_epi16(w1, _mm256_cmpgt_epi16(keyLimit[1], load(r + kLanes)));
            w2 = _mm256_add_epi16(w2, _mm256_cmpgt_epi16(keyLimit[2], load(r + 2 * kLanes)));
            w3 = _mm256_add_epi16(w3, _mm256_cmpgt_epi16(keyLimit[3], load(r + 3 * kLanes)));
          }
          c = row(c, 8 * s);
          // Each sum back in its accumulator's register (else 4 moves).
          asm("" : "+x"(w0), "+x"(w1), "+x"(w2), "+x"(w3));
        } while (c != end);
        within[0] = w0;
        within[1] = w1;
        within[2] = w2;
        within[3] = w3;
      }
      for (int n = 0; n < kBlocks; ++n) {
        const int i = i0 + n * kLanes;
        if (i >= to) break;
        finishLeft<kShift>(best[n], lane[n], limit[n],
                           _mm256_sub_epi16(_mm256_setzero_si256(), within[n]), i,
                           std::min(kLanes, to - i), outDisparity + x0_);
      }
    }
  }

  // The last steps of decideLeft for the 16 pixels from i, of which the
  // first `valid` are written to out[i ..]: C(b - 1) and C(b + 1) by gathers
  // of 32 bits at 16-bit entries (the entry after each is inside the row's
  // edge; rows -1 and count hold "no cost"), then texture, uniqueness
  // (limit: saturated at 65535; within: lanes with cost <= limit) and the
  // sub-pixel step.
  template <int kShift>
  HOROPTER_AVX2_TARGET void finishLeft(__m256i bestKey, __m256i lane, __m256i limit, __m256i within,
                                       int i, int valid, std::int16_t* out) const {
    const __m256i bias16 = _mm256_set1_epi16(static_cast<std::int16_t>(kBias));
    const __m256i ones = _mm256_set1_epi16(-1);
    const __m256i zero = _mm256_setzero_si256();
    const __m256i key = _mm256_xor_si256(bestKey, bias16);
    const __m256i least = _mm256_srli_epi16(key, kShift);
    // The group's index plus its key bits times count / G (leastKeys).
    const __m256i b = _mm256_add_epi16(
        lane, _mm256_mullo_epi16(_mm256_and_si256(key, _mm256_set1_epi16((1 << kShift) - 1)),
                                 _mm256_set1_epi16(static_cast<std::int16_t>(count_ >> kShift))));

    const __m256i rowLenV = _mm256_set1_epi32(rowLen_);
    const __m256i step8 = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    const __m256i offLo = _mm256_add_epi32(
        _mm256_mullo_epi32(_mm256_cvtepu16_epi32(_mm256_castsi256_si128(b)), rowLenV),
        _mm256_add_epi32(_mm256_set1_epi32(i), step8));
    const __m256i offHi = _mm256_add_epi32(
        _mm256_mullo_epi32(_mm256_cvtepu16_epi32(_mm256_extracti128_si256(b, 1)), rowLenV),
        _mm256_add_epi32(_mm256_set1_epi32(i + 8), step8));
    const __m256i low16 = _mm256_set1_epi32(0xFFFF);
    // The cost of the entries at row `row` (relative to row 0) and the
    // offsets; "no cost" stays 65535.
    const auto neighbourCosts = [&](const std::int16_t* row) HOROPTER_AVX2_TARGET {
      const auto* p = reinterpret_cast<const int*>(row);
      const __m256i lo = _mm256_and_si256(_mm256_i32gather_epi32(p, offLo, 2), low16);
      const __m256i hi = _mm256_and_si256(_mm256_i32gather_epi32(p, offHi, 2), low16);
      const __m256i keys =
          _mm256_xor_si256(_mm256_permute4x64_epi64(_mm256_packus_epi32(lo, hi), 0xD8), bias16);
      return _mm256_or_si256(_mm256_srli_epi16(keys, kShift), _mm256_cmpeq_epi16(keys, ones));
    };
    // With a folded guard, row -1 is lane minD - 1, not "no cost". At b = 0
    // that changes nothing: where it is <= the limit, so is the guard's
    // least, and the pixel is invalid; cm takes `above` there.
    const __m256i below = neighbourCosts(costs(-1));
    const __m256i above = neighbourCosts(costs(1));

    __m256i bad = zero;
    if (useTexture_) {
      const __m256i threshold = _mm256_set1_epi32(params_.textureThreshold);
      const int* texture = pxTexture_.get() + i;
      bad = _mm256_permute4x64_epi64(
          _mm256_packs_epi32(_mm256_cmpgt_epi32(threshold, load8x32(texture)),
                             _mm256_cmpgt_epi32(threshold, load8x32(texture + 8))),
          0xD8);
    }
    if (params_.uniquenessRatio > 0) {
      // x <= limit, unsigned.
      const auto atMost = [&](__m256i x) HOROPTER_AVX2_TARGET {
        return _mm256_cmpeq_epi16(_mm256_max_epu16(x, limit), limit);
      };
      // 1 + [below <= limit] + [above <= limit]; a limit of 65535 or more
      // takes in every lane.
      const __m256i expected =
          _mm256_sub_epi16(_mm256_sub_epi16(_mm256_set1_epi16(1), atMost(below)), atMost(above));
      bad = _mm256_or_si256(bad, _mm256_xor_si256(_mm256_cmpeq_epi16(within, expected), ones));
      bad = _mm256_or_si256(bad, _mm256_cmpeq_epi16(limit, ones));
    }
    if (guards_ > 0) {
      // The guard's least <= the limit (the least cost when the uniqueness
      // test is off), unsigned; 65535 (none) is above every real limit.
      const __m256i guardLimit = params_.uniquenessRatio > 0 ? limit : least;
      const __m256i g = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(guardLeast_.get() + i));
      bad = _mm256_or_si256(bad, _mm256_cmpeq_epi16(_mm256_max_epu16(g, guardLimit), guardLimit));
    }

    // At the ends of the range the missing side mirrors the other. With
    // c0 the least cost, den = cm + cp - 2 c0 + |cm - cp| = 2 (max - c0), so
    // off = (cm - cp) * 256 / den = 128 (cm - cp) / (max - c0), truncated.
    const __m256i cm = _mm256_blendv_epi8(below, above, _mm256_cmpeq_epi16(b, zero));
    const __m256i cp =
        _mm256_blendv_epi8(above, below, _mm256_cmpeq_epi16(b, _mm256_set1_epi16(count_ - 1)));
    const __m256i spread = _mm256_sub_epi16(_mm256_max_epu16(cm, cp), least);  // >= 0
    // One half of 8 pixels in 32 bits. The quotient in float is exact:
    // |128 (cm - cp)| < 2^23 and 0 < spread < 2^16, so the rounded quotient
    // (<= 128, error under 2^-18) cannot cross an integer (at least 1/spread
    // away unless it is one).
    const auto half = [&](__m128i cm8, __m128i cp8, __m128i spread8,
                          __m128i b8) HOROPTER_AVX2_TARGET {
      const __m256i s = _mm256_cvtepu16_epi32(spread8);
      const __m256i num = _mm256_slli_epi32(
          _mm256_sub_epi32(_mm256_cvtepu16_epi32(cm8), _mm256_cvtepu16_epi32(cp8)), 7);
      const __m256i quotient = _mm256_cvttps_epi32(_mm256_div_ps(
          _mm256_cvtepi32_ps(num), _mm256_cvtepi32_ps(_mm256_max_epi32(s, _mm256_set1_epi32(1)))));
      const __m256i off = _mm256_and_si256(quotient, _mm256_cmpgt_epi32(s, _mm256_setzero_si256()));
      const __m256i d = _mm256_add_epi32(_mm256_cvtepu16_epi32(b8), _mm256_set1_epi32(minD_));
      return _mm256_srai_epi32(
          _mm256_add_epi32(_mm256_add_epi32(_mm256_slli_epi32(d, 8), off), _mm256_set1_epi32(8)),
          4);
    };
    const __m256i lo = half(_mm256_castsi256_si128(cm), _mm256_castsi256_si128(cp),
                            _mm256_castsi256_si128(spread), _mm256_castsi256_si128(b));
    const __m256i hi = half(_mm256_extracti128_si256(cm, 1), _mm256_extracti128_si256(cp, 1),
                            _mm256_extracti128_si256(spread, 1), _mm256_extracti128_si256(b, 1));
    const __m256i result =
        _mm256_blendv_epi8(_mm256_permute4x64_epi64(_mm256_packs_epi32(lo, hi), 0xD8),
                           _mm256_set1_epi16(invalidDisparity(params_)), bad);
    if (valid == kLanes) {
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + i), result);
    } else {
      alignas(32) std::int16_t lanes[kLanes];
      store(lanes, result);
      std::copy_n(lanes, valid, out + i);
    }
  }

  // The right view's winners of one row, 16 right pixels per vector: right
  // pixel xr meets lane k in pixel i = xr + minD + k - x0, so lane k's costs
  // for 16 consecutive xr are 16 consecutive entries of its row. The least
  // key (leastKeys) keeps the smallest d on ties; entries outside the
  // region's pixels are "no cost", and every xr written has a real one.
  template <int kShift>
  HOROPTER_AVX2_TARGET void decideRight(std::int16_t* outWinner, int xr0, int xrHigh) const {
    constexpr int kBlocks = kChunk / kLanes;  // blocks of 16 right pixels per pass
    __m256i best[kBlocks], d[kBlocks];
    leastKeys<kShift, kBlocks>(costs(0) + (xr0 + minD_ - x0_), rowLen_ + 1, count_,
                               disparityOf_.get(), best, d);
    if (rightLeastRow_ != nullptr && xr0 < rightLeastEnd_) {
      // The least costs for the left band (exportRightLeast): "no cost" and
      // right pixels past xrHigh (past the costs' rows) as 65535.
      const __m256i bias16 = _mm256_set1_epi16(static_cast<std::int16_t>(kBias));
      const __m256i noCost = _mm256_set1_epi16(kNoCost);
      const __m256i high = _mm256_set1_epi16(static_cast<std::int16_t>(xrHigh - xr0));
      const __m256i lane = _mm256_setr_epi16(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
      for (int n = 0; n < kBlocks; ++n) {
        const __m256i past = _mm256_cmpgt_epi16(
            _mm256_add_epi16(lane, _mm256_set1_epi16(static_cast<std::int16_t>(n * kLanes))), high);
        const __m256i least =
            _mm256_or_si256(_mm256_srli_epi16(_mm256_xor_si256(best[n], bias16), kShift),
                            _mm256_or_si256(_mm256_cmpeq_epi16(best[n], noCost), past));
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(rightLeastRow_ + xr0 + n * kLanes), least);
      }
    }
    const __m256i lowBits = _mm256_set1_epi16((1 << kShift) - 1);
    const __m256i groups = _mm256_set1_epi16(static_cast<std::int16_t>(count_ >> kShift));
    for (int n = 0; n < kBlocks; ++n)
      d[n] = _mm256_add_epi16(d[n], _mm256_mullo_epi16(_mm256_and_si256(best[n], lowBits), groups));
    if (guards_ == 0 && xr0 + kChunk <= xrHigh + 1) {
      // No guard, 4 whole blocks (all but a row's last pass): stored
      // straight from the registers (the arrays went through the stack).
      for (int n = 0; n < kBlocks; ++n)
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(outWinner + xr0 + n * kLanes), d[n]);
      return;
    }
    if (guardGroups_ > 0) {
      // A folded guard's candidates: its lanes' least key (the smallest g on
      // ties), written as min(g, minD - 2); it wins where its cost is <= the
      // range's least (keys with their low bits cleared; "no cost", above
      // every real key so cleared, never wins).
      const int lanes = guardGroups_ * kLanes;
      __m256i guardBest[kBlocks], guardD[kBlocks];
      leastKeys<kShift, kBlocks>(costs(-lanes) + (xr0 + sweepMin_ - x0_), rowLen_ + 1, lanes,
                                 guardDisparityOf_.get(), guardBest, guardD);
      const __m256i high = _mm256_set1_epi16(static_cast<std::int16_t>(~((1 << kShift) - 1)));
      const __m256i top = _mm256_set1_epi16(static_cast<std::int16_t>(minD_ - 2));
      const __m256i guardGroupsV = _mm256_set1_epi16(static_cast<std::int16_t>(lanes >> kShift));
      for (int n = 0; n < kBlocks; ++n) {
        const __m256i g = _mm256_min_epi16(
            _mm256_add_epi16(guardD[n], _mm256_mullo_epi16(_mm256_and_si256(guardBest[n], lowBits),
                                                           guardGroupsV)),
            top);
        const __m256i loses = _mm256_cmpgt_epi16(_mm256_and_si256(guardBest[n], high),
                                                 _mm256_and_si256(best[n], high));
        d[n] = _mm256_blendv_epi8(g, d[n], loses);
      }
    } else if (guards_ > 0) {
      // The guard's candidates, in increasing g: a strict < (unsigned, by
      // the bias) keeps the smallest g; it wins where <= the range's least.
      const __m256i bias16 = _mm256_set1_epi16(static_cast<std::int16_t>(kBias));
      for (int b = 0; b < kBlocks; ++b) {
        const int xr = xr0 + b * kLanes;
        const __m256i least = _mm256_srli_epi16(_mm256_xor_si256(best[b], bias16), kShift);
        __m256i guardLeast = _mm256_set1_epi16(-1), guardD = _mm256_setzero_si256();
        for (int n = guards_ - 1; n >= 0; --n) {
          const int g = guardDisparity(n);
          const __m256i c =
              _mm256_loadu_si256(reinterpret_cast<const __m256i*>(guardCosts(n) + (xr + g - x0_)));
          const __m256i better =
              _mm256_cmpgt_epi16(_mm256_xor_si256(guardLeast, bias16), _mm256_xor_si256(c, bias16));
          guardLeast = _mm256_blendv_epi8(guardLeast, c, better);
          guardD = _mm256_blendv_epi8(
              guardD, _mm256_set1_epi16(static_cast<std::int16_t>(std::min(g, minD_ - 2))), better);
        }
        const __m256i wins = _mm256_cmpeq_epi16(_mm256_max_epu16(guardLeast, least), least);
        d[b] = _mm256_blendv_epi8(d[b], guardD, wins);
      }
    }
    for (int n = 0; n < kBlocks; ++n) {
      const int xr = xr0 + n * kLanes;
      if (xr + kLanes <= xrHigh + 1) {
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(outWinner + xr), d[n]);
      } else if (xr <= xrHigh) {
        alignas(32) std::int16_t lanes[kLanes];
        store(lanes, d[n]);
        std::copy_n(lanes, xrHigh + 1 - xr, outWinner + xr);
      }
    }
  }

  const ConstImageView& left_;
  const ConstImageView& right_;
  const ConstImageView& texture_;
  const StereoParams& params_;
  const ImageView& disparity_;
  const ImageView& winnerRight_;
  const int width_, r_, count_, groups_, minD_;
  // A folded guard (step 1 or 2): its checked disparities' span is swept as
  // guardGroups_ more 16-lane groups below the range's, lanes from
  // sweepMin_ (see Strategy, 4).
  const int guardGroups_, sweepGroups_, sweepMin_;
  const int x0_, x1_, xa_, xb_, cols_;
  const int pixels_, padded_, edge_, rowLen_;
  const bool useTexture_;
  // Costs are kept as keys G * C + (k mod G), G = 2^keyShift (see Strategy);
  // keyInit_ is the running sums' start: the bias and each lane's key bits,
  // [sweep group][16].
  const int keyShift_;
  // Every |L - R| <= 127: the sweep takes it as a signed byte difference.
  const bool narrow_;
  // Every cost times the uniqueness ratio is below 2^23: the limit's
  // division by 100 is done in float (divideBy100Below2Pow23).
  const bool smallProducts_;
  // M > 0 where floor(c * ratio / 100) = floor(c * M / 2^(16 + limitShift_))
  // for every cost c this call can have: the uniqueness limit in 16 bits,
  // one vpmulhuw and a shift (limitMultiplier).
  const int limitMultiplier_, limitShift_;
  AlignedArray<std::int16_t> keyInit_;
  AlignedArray<std::int16_t> columnSum_;       // [g][x - xa + 1][16]; column xa - 1 stays zero
  AlignedArray<std::uint16_t> columnTexture_;  // [x - xa + 1]; index 0 and the tail stay zero
  AlignedArray<int> texturePrefix_;            // [j]: prefix sums of the texture column sums
  // Unpaired group: [x - xa] = the entering row's left pixel | the leaving
  // row's << 8; reversed right rows' bytes interleaved the same way (from
  // the front padding on).
  AlignedArray<std::int16_t> leftPairs_;
  AlignedArray<std::uint8_t> rightPairs_;
  AlignedArray<std::uint8_t> reversedIn_, reversedOut_;  // right rows, reversed
  AlignedArray<std::int16_t> costs_;                     // [k + 1][edge + i + edge], biased
  AlignedArray<std::int16_t> laneOf_;                    // [k][16] = k
  AlignedArray<std::int16_t> disparityOf_;               // [k][16] = minD + k
  AlignedArray<int> pxTexture_;                          // per pixel i = x - x0: texture window sum
  const int guardStep_, guards_, guardStride_;           // guards_: checked disparities
  AlignedArray<std::uint16_t> guardColumns_;             // [n][x - xa]: column sums
  AlignedArray<std::uint16_t> guardLeast_;               // [i]: least window cost (65535: none)
  const int guardEdge_, guardRowLen_;
  AlignedArray<std::uint16_t> guardCosts_;       // [n][guardEdge + i]: window costs (65535: none)
  AlignedArray<std::int16_t> guardDisparityOf_;  // folded: [k][16] = sweepMin + k
  std::int16_t* const laneZero_;                 // costs(0)
  int guardNoCostLeast_ = 1 << 30;               // least guardNoCostFrom over the folded lanes
  // exportRightLeast's array (null: off) and the current row's part of it.
  std::uint16_t* rightLeast_ = nullptr;
  std::ptrdiff_t rightLeastStride_ = 0;
  int rightLeastEnd_ = 0, rightLeastY0_ = 0;
  std::uint16_t* rightLeastRow_ = nullptr;
};

}  // namespace

HOROPTER_AVX2_TARGET void matchBlocks(const ConstImageView& left, const ConstImageView& right,
                                      const ConstImageView& texture, const StereoParams& params,
                                      const BelowRangeGuard& guard, const ImageView& disparity,
                                      const ImageView& winnerRight, RowRange rows) {
  const int width = left.width;
  const int r = params.blockSize / 2;
  const std::int16_t invalid = invalidDisparity(params);
  const auto noWinner = static_cast<std::int16_t>(params.minDisparity - 1);
  MatchRegion region = matchRegion(width, left.height, params);
  region.y0 = std::max(region.y0, rows.begin);
  region.y1 = std::min(region.y1, rows.end);
  // The matcher writes every pixel of the region's rows in [x0, x1) and
  // every right pixel in [x0 - maxD, x1 - 1 - minD] (Matcher::rowPass);
  // the rest is filled here (0.4 M instructions a 1280x720 frame for
  // whole rows).
  const int xrLow = region.x0 - (params.minDisparity + params.numDisparities - 1);
  const int xrEnd = region.x1 - params.minDisparity;
  for (int y = rows.begin; y < rows.end; ++y) {
    std::int16_t* d = disparity.row<std::int16_t>(y);
    std::int16_t* w = winnerRight.row<std::int16_t>(y);
    if (region.empty() || y < region.y0 || y >= region.y1) {
      std::fill_n(d, width, invalid);
      std::fill_n(w, width, noWinner);
      continue;
    }
    std::fill_n(d, region.x0, invalid);
    std::fill(d + region.x1, d + width, invalid);
    std::fill_n(w, xrLow, noWinner);
    std::fill(w + xrEnd, w + width, noWinner);
  }
  if (region.empty()) return;

  int lLo = 255, lHi = 0, rLo = 255, rHi = 0;
  scanRange(left, region.y0 - r, region.y1 + r, lLo, lHi);
  scanRange(right, region.y0 - r, region.y1 + r, rLo, rHi);
  const std::int64_t maxDiff = std::max({lHi - rLo, rHi - lLo, 0});
  const std::int64_t side = params.blockSize;
  // Costs must stay below 65535, the "no cost" marker.
  if (maxDiff * side * side >= 0xFFFF) {
    scalar::matchBlocks(left, right, texture, params, guard, disparity, winnerRight, rows);
    return;
  }
  // Keys G * cost + (k mod G), G = 2^shift, must stay below 65535 too.
  int shift = 0;
  while (shift < 3 && ((maxDiff * side * side) << (shift + 1)) + (2 << shift) - 1 < 0xFFFF)
    ++shift;
  const bool smallProducts = maxDiff * side * side * params.uniquenessRatio < (1 << 23);
  Matcher matcher(left, right, texture, params, guard, disparity, winnerRight, region, shift,
                  maxDiff <= 127, smallProducts, static_cast<int>(maxDiff * side * side));
  // The left band (params.leftBand): its own sweep over the disparities that
  // fit there (sad_band_avx2.cpp), under the same cost bound. Without the
  // guard, the region's least cost per right pixel left of x0 - minD lets it
  // cost only the band's own candidates (RegionLeast).
  std::vector<std::uint16_t> least;
  RegionLeast regionLeast;
  if (region.bandX0 < region.x0 && guardCount(params, guard) == 0) {
    regionLeast.stride = ((region.x0 - params.minDisparity + kLanes - 1) & ~(kLanes - 1)) +
                         4 * kLanes;  // the region writes 4 vectors at a time
    least.assign(static_cast<std::size_t>(region.y1 - region.y0) * regionLeast.stride, 0xFFFF);
    regionLeast.least = least.data();
    matcher.exportRightLeast(least.data(), regionLeast.stride, region.x0 - params.minDisparity,
                             region.y0);
  }
  matcher.run(region.y0, region.y1);
  matchLeftBand(left, right, texture, params, guard, disparity, winnerRight, rows,
                maxDiff * side * side, regionLeast);
}

}  // namespace horopter::avx2
