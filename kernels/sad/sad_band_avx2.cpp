// AVX2 left band (StereoParams::leftBand): bit-exact with
// scalar::matchLeftBand, which defines what is computed (sad_scalar.cpp).
//
// Strategy
//   The band's work is a parallelogram in right-pixel coordinates: every
//   cost it reads is C(xr + d, d) for the right pixels xr in [r, rightEnd)
//   (rightEnd = x0 - the lowest disparity checked) and the disparities d
//   from that lowest (the guard's span, when on) to maxD, those with the
//   left pixel xr + d in [bandX0, costedEnd). So the sweep runs along xr,
//   16 disparities to a vector (lanes d = dLo + 16g + k):
//   columnSum[g][c] holds, for the right column c, the column costs
//   |L(c + d) - R(c)| over the window's height; it slides down a row by
//   adding the entering row's and subtracting the leaving row's, both at
//   once: the left pixels c + d of 16 consecutive d are 16 consecutive
//   words (entering | leaving << 8), the right pixel's pair is broadcast,
//   and maddubs with (1, -1) gives in - out. Along c, the window cost of xr
//   takes in column xr + r and drops xr - r - 1 (running sums in registers).
//   Every 16 right pixels the 16 cost vectors are transposed and stored by
//   row: costs[d][xr]. No pixel's window leaves the images: the sweep
//   starts at xr = r, and the left pixels it reads past the image (lanes
//   never read) are zero padding.
//
//   In that layout both decisions are vertical loops over d, 16 pixels a
//   vector: right pixel xr's candidates are row d at xr, left pixel x's are
//   row d at x - d (shifted loads). Entries with xr < r are never written
//   and keep "no cost" (65535, above every real cost, costs being below it
//   by the bound checked first), which ends each band pixel's own range
//   (top(x) = x - r). The sweep ORs precomputed masks into its edge chunks
//   so that every entry no pixel may weigh is "no cost" too (left pixel
//   outside [bandX0, costedEnd), the guard's right window past the image):
//   the decisions' loops carry no lane masks. Winners: running minima in
//   decreasing d with <= (the smallest d on ties; "no cost" wins only where
//   every entry is one). Left pixels: the same minimum, a second pass
//   counting the costs within the uniqueness limit (the winner and those of
//   its neighbours within it, for a valid pixel), the guard's least, then
//   texture, the tests and the integer sub-pixel fit of decidePixel, 16
//   pixels a vector (neighbour costs by gathers).
//
//   Triangle (RegionLeast, no guard): when avx2::matchBlocks's region pass
//   left the least cost of each right pixel over its own candidates, only
//   the candidates with x < x0 are costed (half the parallelogram), and a
//   right pixel's winner among them replaces the region's where its cost is
//   <= the region's least (its d are the smaller, so it wins ties).
//
//   Costs are 16-bit: the caller's bound (maxDiff * blockSize^2) must be
//   below 65535, else the scalar reference runs.
#include <immintrin.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "common/cpu_features.hpp"
#include "sad/sad.hpp"
#include "sad/sad_transpose_avx2.hpp"

namespace horopter::avx2 {

namespace {

constexpr int kLanes = 16;
constexpr std::uint16_t kNoCost = 0xFFFF;

HOROPTER_AVX2_TARGET inline __m256i loadu(const void* p) {
  return _mm256_loadu_si256(static_cast<const __m256i*>(p));
}
HOROPTER_AVX2_TARGET inline void storeu(void* p, __m256i v) {
  _mm256_storeu_si256(static_cast<__m256i*>(p), v);
}

// Eight int32 lanes (0 <= n < 2^31) divided by 100, truncated: exact in
// double (n / 100 lies at least 0.01 from the next integer).
HOROPTER_AVX2_TARGET inline __m256i divideBy100(__m256i n) {
  const __m256d hundred = _mm256_set1_pd(100.0);
  const __m128i lo =
      _mm256_cvttpd_epi32(_mm256_div_pd(_mm256_cvtepi32_pd(_mm256_castsi256_si128(n)), hundred));
  const __m128i hi = _mm256_cvttpd_epi32(
      _mm256_div_pd(_mm256_cvtepi32_pd(_mm256_extracti128_si256(n, 1)), hundred));
  return _mm256_set_m128i(hi, lo);
}

// Eight int32 lanes n / d truncated toward zero (|n| < 2^31, 0 < d < 2^31):
// exact in double.
HOROPTER_AVX2_TARGET inline __m256i divideTruncated(__m256i n, __m256i d) {
  const __m128i lo =
      _mm256_cvttpd_epi32(_mm256_div_pd(_mm256_cvtepi32_pd(_mm256_castsi256_si128(n)),
                                        _mm256_cvtepi32_pd(_mm256_castsi256_si128(d))));
  const __m128i hi =
      _mm256_cvttpd_epi32(_mm256_div_pd(_mm256_cvtepi32_pd(_mm256_extracti128_si256(n, 1)),
                                        _mm256_cvtepi32_pd(_mm256_extracti128_si256(d, 1))));
  return _mm256_set_m128i(hi, lo);
}

// The uniqueness limits c + c * ratio / 100 of 16 costs, clamped to 65534:
// for a real cost (< 65535), C <= limit iff C <= the clamped limit, and
// "no cost" is above it.
HOROPTER_AVX2_TARGET inline __m256i uniquenessLimits(__m256i c0, int ratio) {
  const __m256i r = _mm256_set1_epi32(ratio);
  const __m256i top = _mm256_set1_epi32(kNoCost - 1);
  __m256i half[2];
  for (int h = 0; h < 2; ++h) {
    const __m256i c = _mm256_cvtepu16_epi32(h == 0 ? _mm256_castsi256_si128(c0)
                                                   : _mm256_extracti128_si256(c0, 1));
    half[h] = _mm256_min_epi32(_mm256_add_epi32(c, divideBy100(_mm256_mullo_epi32(c, r))), top);
  }
  return _mm256_permute4x64_epi64(_mm256_packus_epi32(half[0], half[1]), 0xD8);
}

class BandMatcher {
 public:
  HOROPTER_AVX2_TARGET BandMatcher(const ConstImageView& left, const ConstImageView& right,
                                   const ConstImageView& texture, const StereoParams& params,
                                   const BelowRangeGuard& guard, const ImageView& disparity,
                                   const ImageView& winnerRight, const MatchRegion& region,
                                   const scalar::ColumnWindow& window, bool narrow,
                                   const RegionLeast& regionLeast)
      : left_(left),
        right_(right),
        texture_(texture),
        params_(params),
        disparity_(disparity),
        winnerRight_(winnerRight),
        width_(left.width),
        r_(params.blockSize / 2),
        count_(params.numDisparities),
        minD_(params.minDisparity),
        maxD_(params.minDisparity + params.numDisparities - 1),
        guards_(guardCount(params, guard)),
        guardStep_(guard.step),
        x0_(region.x0),
        bandX0_(region.bandX0),
        // scalar::leftBandWindow, as matchLeftBand costs it.
        rightEnd_(window.rightEnd),
        costedEnd_(std::min(region.x1, window.costedEnd)),
        rightEndW_(std::clamp(rightEnd_, 0, width_)),
        dLo_(minD_ - guards_ * guardStep_),
        groups_((maxD_ - dLo_ + kLanes) / kLanes),
        useTexture_(params.textureThreshold > 0),
        narrow_(narrow),
        triangle_(regionLeast.least != nullptr && guards_ == 0),
        regionLeast_(regionLeast),
        y0_(region.y0) {
    // Per group: the right pixels it costs, [xrStart, xrStart + 16 * chunks).
    int columnsEnd = 0, lowest = 0, highest = 0;
    for (int g = 0; g < groups_; ++g) {
      const int dMin = dLo_ + kLanes * g, dMax = dMin + kLanes - 1;
      const int start = std::max(r_, bandX0_ - dMax);
      const int end = std::min({rightEnd_, costedEnd_ - dMin, width_ - r_, bandEnd(dMin)});
      const int chunks = end > start ? (end - start + kLanes - 1) / kLanes : 0;
      xrStart_.push_back(start);
      chunks_.push_back(chunks);
      if (chunks == 0) continue;
      const int cEnd = start + kLanes * chunks + r_;
      columnsEnd = std::max(columnsEnd, cEnd);
      lowest = std::min(lowest, start - r_ + dMin);
      highest = std::max(highest, cEnd + dMax + 1);
    }
    columnsEnd_ = columnsEnd;
    // "No cost" masks of the chunks that hold entries no pixel may weigh
    // (see Strategy): [g][chunk][k][j], all ones where (d, xr) is invalid.
    for (int g = 0; g < groups_; ++g) {
      chunkBase_.push_back(static_cast<int>(maskIndex_.size()));
      for (int chunk = 0; chunk < chunks_[g]; ++chunk) {
        bool any = false;
        for (int k = 0; k < kLanes; ++k) {
          const int d = dLo_ + kLanes * g + k;
          const int valid0 = std::max(r_, bandX0_ - d);
          const int valid1 = std::min({rightEnd_, costedEnd_ - d, width_ - r_, bandEnd(d)});
          for (int j = 0; j < kLanes; ++j) {
            const int xr = xrStart_[g] + kLanes * chunk + j;
            const bool invalid = xr < valid0 || xr >= valid1;
            masks_.push_back(invalid ? kNoCost : 0);
            any = any || invalid;
          }
        }
        if (!any) masks_.resize(masks_.size() - kLanes * kLanes);
        maskIndex_.push_back(any ? static_cast<int>(masks_.size()) - kLanes * kLanes : -1);
      }
    }
    leftOrigin_ = -lowest;
    leftPairs_.assign(static_cast<std::size_t>(highest - lowest + kLanes), 0);
    leftFill_ = std::min(width_, highest);
    rightPairs_.assign(static_cast<std::size_t>(columnsEnd + kLanes), 0);
    rightFill_ = std::min(width_, columnsEnd);
    pad_ = 2 * r_ + 1;
    columnStride_ = (pad_ + columnsEnd) * kLanes;
    columnSums_.assign(static_cast<std::size_t>(groups_) * columnStride_, 0);
    // Cost rows: d from dLo - 1 (a row of "no cost" below) to dLo + 16 *
    // groups; entries xr from -front (left reads reach x - maxD).
    front_ = (count_ + 2 * kLanes) & ~(kLanes - 1);
    // (reads reach 16 entries past rightEnd; gathers 2 bytes past one)
    costStride_ = front_ + std::max(rightEnd_, 0) + 5 * kLanes;
    costs_.assign(static_cast<std::size_t>(kLanes * groups_ + 2) * costStride_ + kLanes, kNoCost);
    zeros_.assign(static_cast<std::size_t>(width_), 0);
    textureColumns_.assign(static_cast<std::size_t>(x0_ + r_ + 8), 0);
    for (int k = 0; k < count_; ++k)
      laneK_.insert(laneK_.end(), kLanes, static_cast<std::int16_t>(k));
    textureSums_.assign(static_cast<std::size_t>(x0_ - bandX0_ + kLanes), 0);
  }

  HOROPTER_AVX2_TARGET void run(int y0, int y1) {
    for (int j = y0 - r_; j < y0 + r_; ++j) {
      preparePairs(j, -1);
      sweep<false>();
      slideTexture(j, -1);
    }
    for (int y = y0; y < y1; ++y) {
      const int in = y + r_, out = y == y0 ? -1 : y - r_ - 1;
      preparePairs(in, out);
      sweep<true>();
      slideTexture(in, out);
      decideLeft(y);
      decideRight(y);
    }
  }

 private:
  HOROPTER_AVX2_TARGET std::uint16_t* costRow(int d) const {
    return const_cast<std::uint16_t*>(costs_.data()) +
           static_cast<std::ptrdiff_t>(d - dLo_ + 1) * costStride_ + front_;
  }
  // 16 lanes of k (laneK_).
  HOROPTER_AVX2_TARGET __m256i laneK(int k) const { return loadu(laneK_.data() + kLanes * k); }
  HOROPTER_AVX2_TARGET int guardDisparity(int n) const { return minD_ - (n + 1) * guardStep_; }
  // The right pixels costed at d end where the left pixel reaches x0 when
  // the region's least costs are known (triangle_).
  HOROPTER_AVX2_TARGET int bandEnd(int d) const { return triangle_ ? x0_ - d : 1 << 30; }

  // leftPairs_[x] = L(x, in) | L(x, out) << 8, rightPairs_[c] the same of R
  // (out < 0: zeros, the first rows' warm-up).
  HOROPTER_AVX2_TARGET void preparePairs(int in, int out) {
    const auto interleave = [](const std::uint8_t* a, const std::uint8_t* b, int n,
                               std::uint16_t* dst) HOROPTER_AVX2_TARGET {
      int i = 0;
      for (; i + 32 <= n; i += 32) {
        const __m256i va = loadu(a + i), vb = loadu(b + i);
        const __m256i lo = _mm256_unpacklo_epi8(va, vb), hi = _mm256_unpackhi_epi8(va, vb);
        storeu(dst + i, _mm256_permute2x128_si256(lo, hi, 0x20));
        storeu(dst + i + 16, _mm256_permute2x128_si256(lo, hi, 0x31));
      }
      for (; i < n; ++i)
        dst[i] = static_cast<std::uint16_t>(a[i] | b[i] << 8);
    };
    const std::uint8_t* zero = zeros_.data();
    interleave(left_.row<std::uint8_t>(in), out < 0 ? zero : left_.row<std::uint8_t>(out),
               leftFill_, leftPairs_.data() + leftOrigin_);
    interleave(right_.row<std::uint8_t>(in), out < 0 ? zero : right_.row<std::uint8_t>(out),
               rightFill_, rightPairs_.data());
  }

  // Slides every group's column sums down a row (the pairs prepared); with
  // kCosts, the window costs too, stored by row (see Strategy).
  template <bool kCosts>
  HOROPTER_AVX2_TARGET void sweep() {
    if (narrow_)
      sweep<kCosts, true>();
    else
      sweep<kCosts, false>();
  }

  // kNarrow: every |L - R| <= 127, the wrapped byte difference's absolute
  // value is exact (2 instructions instead of 3).
  template <bool kCosts, bool kNarrow>
  HOROPTER_AVX2_TARGET void sweep() {
    const __m256i weights = _mm256_set1_epi16(static_cast<std::int16_t>(0xFF01));
    const int r = r_, side = 2 * r_ + 1;
    const std::ptrdiff_t stride = costStride_;
    const std::uint16_t* const masks = masks_.data();
    for (int g = 0; g < groups_; ++g) {
      const int chunks = chunks_[g];
      if (chunks == 0) continue;
      const int dMin = dLo_ + kLanes * g;
      const int c0 = xrStart_[g] - r;
      const int c1 = c0 + 2 * r + kLanes * chunks;
      const std::uint16_t* const lp = leftPairs_.data() + leftOrigin_ + dMin;
      const std::uint16_t* const rp = rightPairs_.data();
      std::int16_t* const col =
          columnSums_.data() + static_cast<std::ptrdiff_t>(g) * columnStride_ + pad_ * kLanes;
      // Column c's update, from pointers at c (lp + c, rp + c, col + 16c):
      // returns its new column sum.
      const auto update = [&](const std::uint16_t* l, const std::uint16_t* rr,
                              std::int16_t* p) HOROPTER_AVX2_TARGET {
        const __m256i lv = loadu(l);
        const __m256i rb = _mm256_set1_epi16(static_cast<std::int16_t>(*rr));
        __m256i ad;
        if constexpr (kNarrow)
          ad = _mm256_abs_epi8(_mm256_sub_epi8(lv, rb));
        else
          ad = _mm256_or_si256(_mm256_subs_epu8(lv, rb), _mm256_subs_epu8(rb, lv));
        const __m256i v = _mm256_add_epi16(loadu(p), _mm256_maddubs_epi16(ad, weights));
        storeu(p, v);
        return v;
      };
      const std::uint16_t* l = lp + c0;
      const std::uint16_t* rr = rp + c0;
      std::int16_t* p = col + static_cast<std::ptrdiff_t>(c0) * kLanes;
      if constexpr (!kCosts) {
        for (int c = c0; c < c1; ++c, ++l, ++rr, p += kLanes)
          update(l, rr, p);
      } else {
        __m256i sum = _mm256_setzero_si256();
        for (int c = c0; c < c0 + 2 * r; ++c, ++l, ++rr, p += kLanes)
          sum = _mm256_add_epi16(sum, update(l, rr, p));
        const std::ptrdiff_t back = static_cast<std::ptrdiff_t>(side) * kLanes;
        const int* const maskIndex = maskIndex_.data() + chunkBase_[g];
        std::uint16_t* row = costRow(dMin) + xrStart_[g];
        for (int chunk = 0; chunk < chunks;
             ++chunk, row += kLanes, l += kLanes, rr += kLanes, p += kLanes * kLanes) {
          __m256i w[kLanes], t[kLanes];
          const std::int16_t* leaving = p - back;  // column c - 2r - 1
#pragma GCC unroll 16
          for (int j = 0; j < kLanes; ++j) {
            sum = _mm256_sub_epi16(_mm256_add_epi16(sum, update(l + j, rr + j, p + kLanes * j)),
                                   loadu(leaving + kLanes * j));
            w[j] = sum;
          }
          transpose16(w, t);
          if (const int mask = maskIndex[chunk]; mask >= 0) {
            for (int k = 0; k < kLanes; ++k)
              t[k] = _mm256_or_si256(t[k], loadu(masks + mask + kLanes * k));
          }
          std::uint16_t* dst = row;
          for (int k = 0; k < kLanes; ++k, dst += stride)
            storeu(dst, t[k]);
        }
      }
    }
  }

  // Texture column sums over the window's rows, for the band's windows.
  HOROPTER_AVX2_TARGET void slideTexture(int in, int out) {
    if (!useTexture_) return;
    const std::uint8_t* tin = texture_.row<std::uint8_t>(in);
    const std::uint8_t* tout = out < 0 ? zeros_.data() : texture_.row<std::uint8_t>(out);
    for (int x = bandX0_ - r_; x < x0_ + r_; ++x)
      textureColumns_[x] += tin[x] - tout[x];
  }

  HOROPTER_AVX2_TARGET void decideLeft(int y) {
    std::int16_t* out = disparity_.row<std::int16_t>(y);
    const int ratio = params_.uniquenessRatio;
    const __m256i one = _mm256_set1_epi16(1);
    const __m256i iota = _mm256_setr_epi16(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    if (useTexture_) {
      // Window sums of the texture, per band pixel, 8 at a time.
      for (int x = bandX0_; x < x0_; x += 8) {
        const int* column = textureColumns_.data() + x;
        __m256i sum = loadu(column - r_);
        for (int i = -r_ + 1; i <= r_; ++i)
          sum = _mm256_add_epi32(sum, loadu(column + i));
        storeu(textureSums_.data() + (x - bandX0_), sum);
      }
    }
    for (int xv = bandX0_; xv < x0_; xv += kLanes) {
      // Pixels x = xv + j; k above xv + 15 - r - minD has no cost for any.
      const int kEnd = std::min(count_, xv + kLanes - r_ - minD_);
      // The least cost, in decreasing k with <= (the smallest k on ties).
      __m256i m = _mm256_set1_epi16(-1), b = _mm256_setzero_si256();
#pragma GCC unroll 4
      for (int k = kEnd - 1; k >= 0; --k) {
        const int d = minD_ + k;
        const __m256i c = loadu(costRow(d) + xv - d);
        m = _mm256_min_epu16(m, c);
        b = _mm256_blendv_epi8(b, laneK(k), _mm256_cmpeq_epi16(m, c));
      }
      const __m256i lim = ratio > 0 || guards_ > 0 ? uniquenessLimits(m, ratio) : m;
      const __m256i xs = _mm256_add_epi16(iota, _mm256_set1_epi16(static_cast<std::int16_t>(xv)));
      // Each pixel's range: k < n = min(count, x - r - minD + 1).
      const __m256i n = _mm256_min_epi16(
          _mm256_sub_epi16(xs, _mm256_set1_epi16(static_cast<std::int16_t>(r_ + minD_ - 1))),
          _mm256_set1_epi16(static_cast<std::int16_t>(count_)));
      const __m256i hasBelow = _mm256_cmpgt_epi16(b, _mm256_setzero_si256());
      const __m256i hasAbove = _mm256_cmpgt_epi16(n, _mm256_add_epi16(b, one));
      const __m256i below = neighbourCosts(xv, b, -1), above = neighbourCosts(xv, b, 1);
      __m256i invalid = _mm256_setzero_si256();
      if (useTexture_) {
        const __m256i threshold = _mm256_set1_epi32(params_.textureThreshold);
        const __m256i low0 =
            _mm256_cmpgt_epi32(threshold, loadu(textureSums_.data() + (xv - bandX0_)));
        const __m256i low1 =
            _mm256_cmpgt_epi32(threshold, loadu(textureSums_.data() + (xv - bandX0_ + 8)));
        invalid = _mm256_permute4x64_epi64(_mm256_packs_epi32(low0, low1), 0xD8);
      }
      if (ratio > 0) {
        // Valid: the costs within the limit are the winner and those of its
        // neighbours within it (masks are -1).
        __m256i within = _mm256_setzero_si256();
#pragma GCC unroll 4
        for (int k = 0; k < kEnd; ++k) {
          const int d = minD_ + k;
          const __m256i c = loadu(costRow(d) + xv - d);
          within = _mm256_add_epi16(within, _mm256_cmpeq_epi16(_mm256_max_epu16(c, lim), lim));
        }
        const auto le = [&](__m256i c) HOROPTER_AVX2_TARGET {
          return _mm256_cmpeq_epi16(_mm256_max_epu16(c, lim), lim);
        };
        const __m256i neighbours = _mm256_add_epi16(_mm256_and_si256(hasBelow, le(below)),
                                                    _mm256_and_si256(hasAbove, le(above)));
        invalid = _mm256_or_si256(
            invalid, _mm256_xor_si256(_mm256_cmpeq_epi16(within, _mm256_sub_epi16(neighbours, one)),
                                      _mm256_set1_epi16(-1)));
      }
      if (guards_ > 0) {
        // The checked disparities' least (the sweep left "no cost" where
        // one does not count) fails the pixel at or below the limit.
        __m256i gl = _mm256_set1_epi16(-1);
        for (int i = 0; i < guards_; ++i) {
          const int g = guardDisparity(i);
          gl = _mm256_min_epu16(gl, loadu(costRow(g) + xv - g));
        }
        invalid = _mm256_or_si256(invalid, _mm256_cmpeq_epi16(_mm256_max_epu16(gl, lim), lim));
      }
      // Sub-pixel: the range's ends mirror the other side (a range of one:
      // offset 0).
      const __m256i cm =
          _mm256_blendv_epi8(_mm256_blendv_epi8(m, above, hasAbove), below, hasBelow);
      const __m256i cp =
          _mm256_blendv_epi8(_mm256_blendv_epi8(m, below, hasBelow), above, hasAbove);
      __m256i half[2];
      for (int h = 0; h < 2; ++h) {
        const auto widen = [&](__m256i v) HOROPTER_AVX2_TARGET {
          return _mm256_cvtepu16_epi32(h == 0 ? _mm256_castsi256_si128(v)
                                              : _mm256_extracti128_si256(v, 1));
        };
        const __m256i c0 = widen(m), lo = widen(cm), hi = widen(cp);
        const __m256i diff = _mm256_sub_epi32(lo, hi);
        const __m256i den =
            _mm256_add_epi32(_mm256_sub_epi32(_mm256_add_epi32(lo, hi), _mm256_add_epi32(c0, c0)),
                             _mm256_abs_epi32(diff));
        // den = 0 only where cm = cp = c0: numerator 0, any divisor gives 0.
        const __m256i off = divideTruncated(_mm256_slli_epi32(diff, 8),
                                            _mm256_max_epi32(den, _mm256_set1_epi32(1)));
        const __m256i d = _mm256_add_epi32(
            widen(b), _mm256_set1_epi32(minD_));  // b < 2^15: the sign bit is clear
        half[h] = _mm256_srai_epi32(
            _mm256_add_epi32(_mm256_add_epi32(_mm256_slli_epi32(d, 8), off), _mm256_set1_epi32(8)),
            4);
      }
      const __m256i disparity =
          _mm256_blendv_epi8(_mm256_permute4x64_epi64(_mm256_packs_epi32(half[0], half[1]), 0xD8),
                             _mm256_set1_epi16(invalidDisparity(params_)), invalid);
      if (xv + kLanes <= x0_) {
        storeu(out + xv, disparity);
      } else {
        alignas(32) std::int16_t lanes[kLanes];
        _mm256_store_si256(reinterpret_cast<__m256i*>(lanes), disparity);
        std::copy_n(lanes, x0_ - xv, out + xv);
      }
    }
  }

  // C(b + step) of pixels xv + j (step -1 or 1), by gathers: row minD + k,
  // entry x - minD - k, i.e. costs_[base + x + k * (stride - 1)].
  HOROPTER_AVX2_TARGET __m256i neighbourCosts(int xv, __m256i b, int step) const {
    const int base = static_cast<int>(costRow(minD_) - costs_.data()) - minD_ + xv;
    const __m256i slope = _mm256_set1_epi32(costStride_ - 1);
    const __m256i low = _mm256_set1_epi32(0xFFFF);
    __m256i half[2];
    for (int h = 0; h < 2; ++h) {
      const __m256i k =
          _mm256_add_epi32(_mm256_cvtepi16_epi32(h == 0 ? _mm256_castsi256_si128(b)
                                                        : _mm256_extracti128_si256(b, 1)),
                           _mm256_set1_epi32(step));
      const __m256i index =
          _mm256_add_epi32(_mm256_add_epi32(_mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7),
                                            _mm256_set1_epi32(base + 8 * h)),
                           _mm256_mullo_epi32(k, slope));
      half[h] = _mm256_and_si256(
          _mm256_i32gather_epi32(reinterpret_cast<const int*>(costs_.data()), index, 2), low);
    }
    return _mm256_permute4x64_epi64(_mm256_packus_epi32(half[0], half[1]), 0xD8);
  }

  // 16 right pixels at a time. Every entry a right pixel may not weigh is
  // "no cost" (the sweep's masks), so these are plain running minima: in
  // decreasing d with <=, the smallest d wins ties; "no cost" entries win
  // only where every entry is one, and there the pixel has no winner.
  HOROPTER_AVX2_TARGET void decideRight(int y) {
    std::int16_t* out = winnerRight_.row<std::int16_t>(y);
    const __m256i all = _mm256_set1_epi16(-1);
    const __m256i noWinner = _mm256_set1_epi16(static_cast<std::int16_t>(minD_ - 1));
    for (int xr = 0; xr < rightEndW_; xr += kLanes) {
      // (triangle_: rows above x0 - 1 - xr hold no cost of these pixels)
      const int top = triangle_ ? std::min(maxD_, x0_ - 1 - xr) : maxD_;
      __m256i least = all, winner = all;
      const std::uint16_t* row = costRow(top) + xr;
#pragma GCC unroll 4
      for (int d = top; d >= minD_; --d, row -= costStride_) {
        const __m256i c = loadu(row);
        least = _mm256_min_epu16(least, c);
        winner = _mm256_blendv_epi8(winner, laneK(d - minD_), _mm256_cmpeq_epi16(least, c));
      }
      winner = _mm256_add_epi16(winner, _mm256_set1_epi16(static_cast<std::int16_t>(minD_)));
      const __m256i none = _mm256_cmpeq_epi16(least, all);
      if (triangle_) {
        // The band's winner where it has one and its cost is <= the
        // region's least (its d are the smaller); else the region's.
        __m256i region;
        if (xr + kLanes <= rightEndW_) {
          region = loadu(out + xr);
        } else {
          alignas(32) std::int16_t lanes[kLanes] = {};
          std::copy_n(out + xr, rightEndW_ - xr, lanes);
          region = _mm256_load_si256(reinterpret_cast<const __m256i*>(lanes));
        }
        const __m256i regionLeast =
            loadu(regionLeast_.least + (y - y0_) * regionLeast_.stride + xr);
        const __m256i wins = _mm256_andnot_si256(
            none, _mm256_cmpeq_epi16(_mm256_max_epu16(least, regionLeast), regionLeast));
        winner = _mm256_blendv_epi8(region, winner, wins);
      } else {
        winner = _mm256_blendv_epi8(winner, noWinner, none);
      }
      if (guards_ > 0) {
        // The checked disparities: the least (the smallest g on ties, in
        // decreasing g with <=) wins where it is <= the range's least and
        // the pixel has a winner.
        __m256i gl = all, gd = all;
        for (int n = 0; n < guards_; ++n) {
          const int g = guardDisparity(n);
          const __m256i c = loadu(costRow(g) + xr);
          gl = _mm256_min_epu16(gl, c);
          gd = _mm256_blendv_epi8(
              gd, _mm256_set1_epi16(static_cast<std::int16_t>(std::min(g, minD_ - 2))),
              _mm256_cmpeq_epi16(gl, c));
        }
        const __m256i wins =
            _mm256_andnot_si256(none, _mm256_cmpeq_epi16(_mm256_max_epu16(gl, least), least));
        winner = _mm256_blendv_epi8(winner, gd, wins);
      }
      if (xr + kLanes <= rightEndW_) {
        storeu(out + xr, winner);
      } else {
        alignas(32) std::int16_t lanes[kLanes];
        _mm256_store_si256(reinterpret_cast<__m256i*>(lanes), winner);
        std::copy_n(lanes, rightEndW_ - xr, out + xr);
      }
    }
  }

  const ConstImageView& left_;
  const ConstImageView& right_;
  const ConstImageView& texture_;
  const StereoParams& params_;
  const ImageView& disparity_;
  const ImageView& winnerRight_;
  const int width_, r_, count_, minD_, maxD_;
  const int guards_, guardStep_;
  const int x0_, bandX0_;
  // Right pixels [0, rightEnd) written (rightEndW_ of them in the image);
  // left pixels [bandX0, costedEnd) costed.
  const int rightEnd_, costedEnd_, rightEndW_;
  // Swept disparities: dLo_ (the lowest checked) .. dLo_ + 16 * groups_ - 1.
  const int dLo_, groups_;
  const bool useTexture_;
  const bool narrow_;  // every |L - R| <= 127 (x-Sobel inputs)
  // The region's least costs are known (RegionLeast, no guard): only the
  // band's own candidates (x < x0) are costed, and a right pixel's winner
  // from them replaces the region's where its cost is <= the region's least.
  const bool triangle_;
  const RegionLeast regionLeast_;
  const int y0_;
  std::vector<int> xrStart_, chunks_;  // per group
  std::vector<int> chunkBase_;         // per group: its first chunk's index in maskIndex_
  std::vector<int> maskIndex_;         // per chunk: its masks' offset in masks_, -1: none
  std::vector<std::uint16_t> masks_;
  int columnsEnd_ = 0;
  int leftOrigin_ = 0, leftFill_ = 0, rightFill_ = 0;
  std::vector<std::uint16_t> leftPairs_;   // [leftOrigin + x]
  std::vector<std::uint16_t> rightPairs_;  // [c]
  int pad_ = 0, columnStride_ = 0;
  std::vector<std::int16_t> columnSums_;  // [g][pad + c][16]; the pad stays zero
  int front_ = 0, costStride_ = 0;
  std::vector<std::uint16_t> costs_;  // [d - dLo + 1][front + xr]
  std::vector<std::uint8_t> zeros_;
  std::vector<int> textureColumns_;  // [x]: texture sums over the window's rows
  std::vector<std::int16_t> laneK_;  // [k][16] = k
  std::vector<int> textureSums_;     // [x - bandX0]: window sums
};

}  // namespace

HOROPTER_AVX2_TARGET void matchLeftBand(const ConstImageView& left, const ConstImageView& right,
                                        const ConstImageView& texture, const StereoParams& params,
                                        const BelowRangeGuard& guard, const ImageView& disparity,
                                        const ImageView& winnerRight, RowRange rows,
                                        std::int64_t costBound, const RegionLeast& regionLeast) {
  MatchRegion region = matchRegion(left.width, left.height, params);
  if (region.empty() || region.bandX0 == region.x0) return;
  region.y0 = std::max(region.y0, rows.begin);
  region.y1 = std::min(region.y1, rows.end);
  if (region.empty()) return;
  const int r = params.blockSize / 2;
  const std::int64_t side = params.blockSize;
  if (costBound < 0) {
    // Blocks up to 15 always fit (255 * 15^2 < 65535); larger ones by the
    // inputs' value ranges over the rows read.
    int lo = 255, hi = 0, rLo = 255, rHi = 0;
    if (side > 15) {
      for (int y = region.y0 - r; y < region.y1 + r; ++y) {
        const auto* l = left.row<std::uint8_t>(y);
        const auto* rr = right.row<std::uint8_t>(y);
        const auto [a, b] = std::minmax_element(l, l + left.width);
        const auto [c, d] = std::minmax_element(rr, rr + right.width);
        lo = std::min<int>(lo, *a);
        hi = std::max<int>(hi, *b);
        rLo = std::min<int>(rLo, *c);
        rHi = std::max<int>(rHi, *d);
      }
      costBound = std::max({hi - rLo, rHi - lo, 0}) * side * side;
    } else {
      costBound = 255 * side * side;
    }
  }
  if (costBound >= kNoCost) {
    scalar::matchLeftBand(left, right, texture, params, guard, disparity, winnerRight, rows);
    return;
  }
  const bool narrow = costBound <= 127 * side * side;
  BandMatcher matcher(left, right, texture, params, guard, disparity, winnerRight, region,
                      scalar::leftBandWindow(region, params, guard), narrow, regionLeast);
  matcher.run(region.y0, region.y1);
}

}  // namespace horopter::avx2
