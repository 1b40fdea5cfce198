// AVX2 normalized-response prefilter: bit-exact with the scalar reference
// (prefilter_normalized_scalar.cpp states the semantics).
//
// Strategy
//   The vertical window sums of a row (int32, 8 per vector) are slid down the
//   rows with one add and one subtract per column; the first row of the range
//   sums its window. The horizontal window sum is a running sum along the row
//   (one add and one subtract per pixel, scalar: a serial chain either way),
//   stored per pixel. The response (cross * G - sum * s) >> 10, its clamp and
//   both outputs are then computed 16 pixels per step in int32 lanes, exact
//   (|cross * G| <= 1530 * 1028 and sum * s <= 65025 * 255 * 171 fit int32),
//   and packed to bytes. Columns 0 and W-1 (whose neighbours replicate the
//   edge), rows narrower than 18 pixels and a last partial step placed flush
//   against the row end (recomputing pixels gives the same bytes) complete it.
#include <immintrin.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "common/cpu_features.hpp"
#include "prefilter/prefilter.hpp"

namespace horopter::avx2 {

namespace {

constexpr int kStep = 16;

HOROPTER_AVX2_TARGET int clampTo(int v, int size) {
  return std::clamp(v, 0, size - 1);
}

// 8 bytes widened to int32 lanes.
HOROPTER_AVX2_TARGET inline __m256i widen8(const std::uint8_t* p) {
  return _mm256_cvtepu8_epi32(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(p)));
}

struct Rows {
  const std::uint8_t* above;
  const std::uint8_t* here;
  const std::uint8_t* below;
};

HOROPTER_AVX2_TARGET void scalarPixel(const Rows& rows, const int* boxSum, int x, int width,
                                      int cap, NormalizedWeights wts, std::uint8_t* outFiltered,
                                      std::uint8_t* outTexture) {
  const int cross = 4 * rows.here[x] + rows.here[clampTo(x - 1, width)] +
                    rows.here[clampTo(x + 1, width)] + rows.above[x] + rows.below[x];
  const int v = (cross * wts.centre - boxSum[x] * wts.mean) >> 10;
  const int clipped = std::clamp(v, -cap, cap);
  if (outFiltered) outFiltered[x] = static_cast<std::uint8_t>(clipped + cap);
  if (outTexture) outTexture[x] = static_cast<std::uint8_t>(std::abs(clipped));
}

// The clamped response of 8 pixels starting at x (1 <= x, x + 8 < width).
HOROPTER_AVX2_TARGET inline __m256i response8(const Rows& rows, const int* boxSum, int x,
                                              __m256i centre, __m256i mean, __m256i lo,
                                              __m256i hi) {
  const __m256i here = widen8(rows.here + x);
  __m256i cross = _mm256_slli_epi32(here, 2);
  cross = _mm256_add_epi32(cross, widen8(rows.here + x - 1));
  cross = _mm256_add_epi32(cross, widen8(rows.here + x + 1));
  cross = _mm256_add_epi32(cross, widen8(rows.above + x));
  cross = _mm256_add_epi32(cross, widen8(rows.below + x));
  const __m256i box = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(boxSum + x));
  const __m256i v = _mm256_srai_epi32(
      _mm256_sub_epi32(_mm256_mullo_epi32(cross, centre), _mm256_mullo_epi32(box, mean)), 10);
  return _mm256_min_epi32(_mm256_max_epi32(v, lo), hi);
}

// 16 int32 values in 0..255 (two vectors, in pixel order) as 16 bytes.
HOROPTER_AVX2_TARGET inline __m128i packBytes(__m256i first, __m256i second) {
  const __m256i words = _mm256_permute4x64_epi64(_mm256_packs_epi32(first, second), 0xD8);
  return _mm_packus_epi16(_mm256_castsi256_si128(words), _mm256_extracti128_si256(words, 1));
}

}  // namespace

HOROPTER_AVX2_TARGET void prefilterNormalized(const ConstImageView& src, int cap, int size,
                                              const ImageView& filtered, const ImageView& texture,
                                              RowRange rows) {
  const int width = src.width;
  const int height = src.height;
  const int r = size / 2;
  const NormalizedWeights wts = normalizedWeights(size);
  std::vector<int> columnSum(static_cast<std::size_t>(width), 0);
  std::vector<int> boxSum(static_cast<std::size_t>(width), 0);
  int* col = columnSum.data();
  const __m256i centre = _mm256_set1_epi32(wts.centre);
  const __m256i mean = _mm256_set1_epi32(wts.mean);
  const __m256i lo = _mm256_set1_epi32(-cap);
  const __m256i hi = _mm256_set1_epi32(cap);
  const __m256i capV = hi;
  // Adds (sign +1) or subtracts a source row into the column sums.
  const auto accumulate = [&](const std::uint8_t* row, bool add) HOROPTER_AVX2_TARGET {
    int x = 0;
    for (; x + 8 <= width; x += 8) {
      const __m256i c = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(col + x));
      const __m256i v = widen8(row + x);
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(col + x),
                          add ? _mm256_add_epi32(c, v) : _mm256_sub_epi32(c, v));
    }
    for (; x < width; ++x)
      col[x] += add ? row[x] : -row[x];
  };
  for (int y = rows.begin; y < rows.end; ++y) {
    if (y == rows.begin) {
      std::fill(columnSum.begin(), columnSum.end(), 0);
      for (int dy = -r; dy <= r; ++dy)
        accumulate(src.row<std::uint8_t>(clampTo(y + dy, height)), true);
    } else {
      accumulate(src.row<std::uint8_t>(clampTo(y + r, height)), true);
      accumulate(src.row<std::uint8_t>(clampTo(y - r - 1, height)), false);
    }
    int sum = 0;
    for (int dx = -r; dx <= r; ++dx)
      sum += col[clampTo(dx, width)];
    boxSum[0] = sum;
    for (int x = 1; x < width; ++x) {
      sum += col[clampTo(x + r, width)] - col[clampTo(x - r - 1, width)];
      boxSum[static_cast<std::size_t>(x)] = sum;
    }
    const Rows three{src.row<std::uint8_t>(clampTo(y - 1, height)), src.row<std::uint8_t>(y),
                     src.row<std::uint8_t>(clampTo(y + 1, height))};
    auto* outFiltered = filtered.empty() ? nullptr : filtered.row<std::uint8_t>(y);
    auto* outTexture = texture.empty() ? nullptr : texture.row<std::uint8_t>(y);
    const int* box = boxSum.data();
    if (width < kStep + 2) {
      for (int x = 0; x < width; ++x)
        scalarPixel(three, box, x, width, cap, wts, outFiltered, outTexture);
      continue;
    }
    scalarPixel(three, box, 0, width, cap, wts, outFiltered, outTexture);
    scalarPixel(three, box, width - 1, width, cap, wts, outFiltered, outTexture);
    // Steps cover [1, width - 1); the last one starts at width - 1 - kStep.
    const int lastStep = width - 1 - kStep;
    for (int x = 1;; x += kStep) {
      x = std::min(x, lastStep);
      const __m256i c0 = response8(three, box, x, centre, mean, lo, hi);
      const __m256i c1 = response8(three, box, x + 8, centre, mean, lo, hi);
      if (outFiltered)
        _mm_storeu_si128(reinterpret_cast<__m128i*>(outFiltered + x),
                         packBytes(_mm256_add_epi32(c0, capV), _mm256_add_epi32(c1, capV)));
      if (outTexture)
        _mm_storeu_si128(reinterpret_cast<__m128i*>(outTexture + x),
                         packBytes(_mm256_abs_epi32(c0), _mm256_abs_epi32(c1)));
      if (x == lastStep) break;
    }
  }
}

}  // namespace horopter::avx2
