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
//   (top(x) = x - r). Right winners mask the lanes whose left pixel lies
//   outside [bandX0, costedEnd) (the first and last 15 rows of a vector) and,
//   for the guard's rows, whose right window leaves the image. Winners:
//   a running minimum with a strict < in increasing d (the smallest d on
//   ties). Left pixels: the same minimum, a second pass counting the costs
//   within the uniqueness limit (the winner and those of its neighbours
//   within it, for a valid pixel), the guard's least, then per pixel the
//   texture sum, the tests and the integer sub-pixel fit, as decidePixel.
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

// Transposes 16 vectors of 16 lanes: t[k] lane j = v[j] lane k.
[[gnu::always_inline]] HOROPTER_AVX2_TARGET inline void transpose16(const __m256i* v, __m256i* t) {
  __m256i w[2][8];
  for (int h = 0; h < 2; ++h) {
    const __m256i* r = v + 8 * h;
    __m256i s[8], u[8];
    for (int m = 0; m < 4; ++m) {
      s[2 * m] = _mm256_unpacklo_epi16(r[2 * m], r[2 * m + 1]);
      s[2 * m + 1] = _mm256_unpackhi_epi16(r[2 * m], r[2 * m + 1]);
    }
    for (int m = 0; m < 2; ++m) {
      u[4 * m] = _mm256_unpacklo_epi32(s[4 * m], s[4 * m + 2]);
      u[4 * m + 1] = _mm256_unpackhi_epi32(s[4 * m], s[4 * m + 2]);
      u[4 * m + 2] = _mm256_unpacklo_epi32(s[4 * m + 1], s[4 * m + 3]);
      u[4 * m + 3] = _mm256_unpackhi_epi32(s[4 * m + 1], s[4 * m + 3]);
    }
    for (int m = 0; m < 4; ++m) {
      w[h][2 * m] = _mm256_unpacklo_epi64(u[m], u[m + 4]);
      w[h][2 * m + 1] = _mm256_unpackhi_epi64(u[m], u[m + 4]);
    }
  }
  for (int c = 0; c < 8; ++c) {
    t[c] = _mm256_permute2x128_si256(w[0][c], w[1][c], 0x20);
    t[c + 8] = _mm256_permute2x128_si256(w[0][c], w[1][c], 0x31);
  }
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
                                   const ImageView& winnerRight, const MatchRegion& region)
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
        // The window of scalar::matchLeftBand (see its comment).
        rightEnd_(region.x0 - (minD_ - guards_ * guardStep_)),
        costedEnd_(std::min(region.x1, rightEnd_ + maxD_)),
        rightEndW_(std::clamp(rightEnd_, 0, width_)),
        dLo_(minD_ - guards_ * guardStep_),
        groups_((maxD_ - dLo_ + kLanes) / kLanes),
        useTexture_(params.textureThreshold > 0) {
    // Per group: the right pixels it costs, [xrStart, xrStart + 16 * chunks).
    int columnsEnd = 0, lowest = 0, highest = width_;
    for (int g = 0; g < groups_; ++g) {
      const int dMin = dLo_ + kLanes * g, dMax = dMin + kLanes - 1;
      const int start = std::max(r_, bandX0_ - dMax);
      const int end = std::min({rightEnd_, costedEnd_ - dMin, width_ - r_});
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
    costStride_ = front_ + std::max(rightEnd_, 0) + 3 * kLanes;
    costs_.assign(static_cast<std::size_t>(kLanes * groups_ + 2) * costStride_, kNoCost);
    zeros_.assign(static_cast<std::size_t>(width_), 0);
    textureColumns_.assign(static_cast<std::size_t>(x0_ + r_), 0);
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
  HOROPTER_AVX2_TARGET int guardDisparity(int n) const { return minD_ - (n + 1) * guardStep_; }

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
    const __m256i weights = _mm256_set1_epi16(static_cast<std::int16_t>(0xFF01));
    const int side = 2 * r_ + 1;
    for (int g = 0; g < groups_; ++g) {
      const int chunks = chunks_[g];
      if (chunks == 0) continue;
      const int dMin = dLo_ + kLanes * g;
      const int c0 = xrStart_[g] - r_;
      const int c1 = c0 + 2 * r_ + kLanes * chunks;
      const std::uint16_t* lp = leftPairs_.data() + leftOrigin_ + dMin;
      const std::uint16_t* rp = rightPairs_.data();
      std::int16_t* col =
          columnSums_.data() + static_cast<std::ptrdiff_t>(g) * columnStride_ + pad_ * kLanes;
      const auto update = [&](int c) HOROPTER_AVX2_TARGET {
        const __m256i l = loadu(lp + c);
        const __m256i rb = _mm256_set1_epi16(static_cast<std::int16_t>(rp[c]));
        const __m256i ad = _mm256_or_si256(_mm256_subs_epu8(l, rb), _mm256_subs_epu8(rb, l));
        std::int16_t* p = col + c * kLanes;
        const __m256i v = _mm256_add_epi16(loadu(p), _mm256_maddubs_epi16(ad, weights));
        storeu(p, v);
        return v;
      };
      if constexpr (!kCosts) {
        for (int c = c0; c < c1; ++c)
          update(c);
      } else {
        __m256i sum = _mm256_setzero_si256();
        for (int c = c0; c < c0 + 2 * r_; ++c)
          sum = _mm256_add_epi16(sum, update(c));
        for (int chunk = 0; chunk < chunks; ++chunk) {
          __m256i w[kLanes], t[kLanes];
          const int cc = c0 + 2 * r_ + kLanes * chunk;
          for (int j = 0; j < kLanes; ++j) {
            const int c = cc + j;
            sum = _mm256_sub_epi16(_mm256_add_epi16(sum, update(c)),
                                   loadu(col + (c - side) * kLanes));
            w[j] = sum;
          }
          transpose16(w, t);
          const int xr = xrStart_[g] + kLanes * chunk;
          for (int k = 0; k < kLanes; ++k)
            storeu(costRow(dMin + k) + xr, t[k]);
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
    const std::int16_t invalid = invalidDisparity(params_);
    const int ratio = params_.uniquenessRatio;
    const __m256i one = _mm256_set1_epi16(1);
    alignas(32) std::uint16_t least[kLanes] = {}, best[kLanes] = {}, limits[kLanes] = {},
                              within[kLanes] = {}, guardLeast[kLanes] = {};
    int textureSum = 0;
    if (useTexture_) {
      for (int i = -r_; i < r_; ++i)
        textureSum += textureColumns_[bandX0_ + i];
    }
    for (int xv = bandX0_; xv < x0_; xv += kLanes) {
      // Pixels x = xv + j; k above xv + 15 - r - minD has no cost for any.
      const int kEnd = std::min(count_, xv + kLanes - r_ - minD_);
      __m256i m = _mm256_set1_epi16(-1), b = _mm256_setzero_si256(), kv = b;
      for (int k = 0; k < kEnd; ++k) {
        const int d = minD_ + k;
        const __m256i c = loadu(costRow(d) + xv - d);
        const __m256i nm = _mm256_min_epu16(m, c);
        b = _mm256_blendv_epi8(kv, b, _mm256_cmpeq_epi16(nm, m));
        m = nm;
        kv = _mm256_add_epi16(kv, one);
      }
      _mm256_store_si256(reinterpret_cast<__m256i*>(least), m);
      _mm256_store_si256(reinterpret_cast<__m256i*>(best), b);
      const bool limited = ratio > 0 || guards_ > 0;
      const __m256i lim = limited ? uniquenessLimits(m, ratio) : m;
      _mm256_store_si256(reinterpret_cast<__m256i*>(limits), lim);
      if (ratio > 0) {
        __m256i n = _mm256_setzero_si256();
        for (int k = 0; k < kEnd; ++k) {
          const int d = minD_ + k;
          const __m256i c = loadu(costRow(d) + xv - d);
          n = _mm256_sub_epi16(n, _mm256_cmpeq_epi16(_mm256_max_epu16(c, lim), lim));
        }
        _mm256_store_si256(reinterpret_cast<__m256i*>(within), n);
      }
      if (guards_ > 0) {
        // Checked disparity g counts where the right window fits:
        // x - g < W - r (the left edge always holds in the band).
        const __m256i xs = _mm256_add_epi16(
            _mm256_setr_epi16(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15),
            _mm256_set1_epi16(static_cast<std::int16_t>(xv)));
        __m256i gl = _mm256_set1_epi16(-1);
        for (int n = 0; n < guards_; ++n) {
          const int g = guardDisparity(n);
          __m256i c = loadu(costRow(g) + xv - g);
          if (xv + kLanes - 1 - g >= width_ - r_)
            c = _mm256_or_si256(
                c, _mm256_cmpgt_epi16(
                       xs, _mm256_set1_epi16(static_cast<std::int16_t>(width_ - r_ - 1 + g))));
          gl = _mm256_min_epu16(gl, c);
        }
        _mm256_store_si256(reinterpret_cast<__m256i*>(guardLeast), gl);
      }
      const int xEnd = std::min(x0_, xv + kLanes);
      for (int x = xv; x < xEnd; ++x) {
        const int j = x - xv;
        if (useTexture_) textureSum += textureColumns_[x + r_];
        out[x] =
            decide(x, best[j], least[j], limits[j], within[j], guardLeast[j], textureSum, invalid);
        if (useTexture_) textureSum -= textureColumns_[x - r_];
      }
    }
  }

  // One band pixel, as scalar decidePixel (its range: k < n).
  HOROPTER_AVX2_TARGET std::int16_t decide(int x, int b, std::int64_t c0, int limit, int within,
                                           int guardLeast, int textureSum,
                                           std::int16_t invalid) const {
    const int n = std::min(count_, x - r_ - minD_ + 1);
    if (useTexture_ && textureSum < params_.textureThreshold) return invalid;
    const auto cost = [&](int k) HOROPTER_AVX2_TARGET -> std::int64_t {
      return costRow(minD_ + k)[x - minD_ - k];
    };
    const std::int64_t below = b > 0 ? cost(b - 1) : 0;
    const std::int64_t above = b + 1 < n ? cost(b + 1) : 0;
    if (params_.uniquenessRatio > 0) {
      const int neighbours = (b > 0 && below <= limit) + (b + 1 < n && above <= limit);
      if (within != 1 + neighbours) return invalid;
    }
    if (guards_ > 0 && guardLeast <= limit) return invalid;
    // The range's ends mirror the other side (a range of one: offset 0).
    const std::int64_t cm = b > 0 ? below : (b + 1 < n ? above : c0);
    const std::int64_t cp = b + 1 < n ? above : (b > 0 ? below : c0);
    const std::int64_t den = cm + cp - 2 * c0 + std::abs(cm - cp);
    const std::int64_t off = den > 0 ? (cm - cp) * 256 / den : 0;
    const std::int64_t d = minD_ + b;
    return static_cast<std::int16_t>((d * 256 + off + 8) >> 4);
  }

  HOROPTER_AVX2_TARGET void decideRight(int y) {
    std::int16_t* out = winnerRight_.row<std::int16_t>(y);
    const __m256i iota = _mm256_setr_epi16(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    const __m256i one = _mm256_set1_epi16(1);
    const __m256i firstX = _mm256_set1_epi16(static_cast<std::int16_t>(bandX0_));
    const __m256i lastX = _mm256_set1_epi16(static_cast<std::int16_t>(costedEnd_ - 1));
    const __m256i all = _mm256_set1_epi16(-1);
    // Lanes whose left pixel xs + d lies outside [bandX0, costedEnd).
    const auto outside = [&](__m256i xs) HOROPTER_AVX2_TARGET {
      return _mm256_or_si256(_mm256_cmpgt_epi16(firstX, xs), _mm256_cmpgt_epi16(xs, lastX));
    };
    for (int xr0 = 0; xr0 < rightEndW_; xr0 += kLanes) {
      const __m256i xr = _mm256_add_epi16(iota, _mm256_set1_epi16(static_cast<std::int16_t>(xr0)));
      __m256i m = all;
      __m256i best = _mm256_set1_epi16(static_cast<std::int16_t>(minD_ - 1));
      // Rows where some lane's left pixel is in [bandX0, costedEnd); all
      // lanes in [full0, full1].
      const int dBegin = std::max(minD_, bandX0_ - xr0 - (kLanes - 1));
      const int dEnd = std::min(maxD_ + 1, costedEnd_ - xr0);
      const int full0 = std::max(dBegin, bandX0_ - xr0);
      const int full1 = std::max(full0, std::min(dEnd, costedEnd_ - xr0 - (kLanes - 1)));
      const auto take = [&](__m256i c, __m256i dv) HOROPTER_AVX2_TARGET {
        const __m256i nm = _mm256_min_epu16(m, c);
        best = _mm256_blendv_epi8(dv, best, _mm256_cmpeq_epi16(nm, m));
        m = nm;
      };
      const auto masked = [&](int d) HOROPTER_AVX2_TARGET {
        const __m256i dv = _mm256_set1_epi16(static_cast<std::int16_t>(d));
        const __m256i c =
            _mm256_or_si256(loadu(costRow(d) + xr0), outside(_mm256_add_epi16(xr, dv)));
        take(c, dv);
      };
      for (int d = dBegin; d < std::min(full0, dEnd); ++d)
        masked(d);
      __m256i dv = _mm256_set1_epi16(static_cast<std::int16_t>(full0));
      for (int d = full0; d < full1; ++d) {
        take(loadu(costRow(d) + xr0), dv);
        dv = _mm256_add_epi16(dv, one);
      }
      for (int d = full1; d < dEnd; ++d)
        masked(d);
      if (guards_ > 0) {
        // The checked disparities in increasing g: the least (the smallest
        // g on ties) wins where it is <= the range's least.
        const __m256i rightTop = _mm256_set1_epi16(static_cast<std::int16_t>(width_ - r_ - 1));
        const __m256i noRightWindow = _mm256_cmpgt_epi16(xr, rightTop);
        __m256i gl = all, gd = _mm256_setzero_si256();
        for (int n = guards_ - 1; n >= 0; --n) {
          const int g = guardDisparity(n);
          const __m256i gv = _mm256_set1_epi16(static_cast<std::int16_t>(g));
          const __m256i c =
              _mm256_or_si256(loadu(costRow(g) + xr0),
                              _mm256_or_si256(outside(_mm256_add_epi16(xr, gv)), noRightWindow));
          const __m256i ngl = _mm256_min_epu16(gl, c);
          gd = _mm256_blendv_epi8(
              _mm256_set1_epi16(static_cast<std::int16_t>(std::min(g, minD_ - 2))), gd,
              _mm256_cmpeq_epi16(ngl, gl));
          gl = ngl;
        }
        const __m256i wins = _mm256_andnot_si256(_mm256_cmpeq_epi16(m, all),
                                                 _mm256_cmpeq_epi16(_mm256_max_epu16(gl, m), m));
        best = _mm256_blendv_epi8(best, gd, wins);
      }
      if (xr0 + kLanes <= rightEndW_) {
        storeu(out + xr0, best);
      } else {
        alignas(32) std::int16_t lanes[kLanes];
        _mm256_store_si256(reinterpret_cast<__m256i*>(lanes), best);
        std::copy_n(lanes, rightEndW_ - xr0, out + xr0);
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
  std::vector<int> xrStart_, chunks_;  // per group
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
};

}  // namespace

HOROPTER_AVX2_TARGET void matchLeftBand(const ConstImageView& left, const ConstImageView& right,
                                        const ConstImageView& texture, const StereoParams& params,
                                        const BelowRangeGuard& guard, const ImageView& disparity,
                                        const ImageView& winnerRight, RowRange rows,
                                        std::int64_t costBound) {
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
  BandMatcher matcher(left, right, texture, params, guard, disparity, winnerRight, region);
  matcher.run(region.y0, region.y1);
}

}  // namespace horopter::avx2
