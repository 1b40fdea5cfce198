// AVX2 prefilter: bit-exact with the scalar reference.
//
// Strategy
//   Lanes: 32 output pixels per step. The bytes at x-1 and x+1 of the three
//   rows are widened to 16-bit lanes (two halves of 16), where the x-Sobel
//   (|sobel| <= 4 * 255) and the clamp to [-cap, cap] are exact; the results
//   are packed back to bytes (packus, then a cross-lane permute to undo the
//   per-128-bit interleave of the pack).
//   Tails: a row of at least 34 pixels ends with one step placed flush
//   against the row end, overlapping the previous one; recomputing pixels
//   writes the same values and touches nothing outside the row. Narrower rows,
//   and columns 0 and W-1 (sobel = 0), take the scalar formula.
//   Rows outside the image reflect (reflect-101) exactly as the reference.
#include <immintrin.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>

#include "common/cpu_features.hpp"
#include "prefilter/prefilter.hpp"

namespace horopter::avx2 {

namespace {

// A private copy of the reference's row reflection (from when this file was
// compiled with -mavx2, and a shared inline function could have become the
// copy the linker keeps for the scalar callers too).
HOROPTER_AVX2_TARGET int reflect101(int y, int height) {
  if (height == 1) return 0;
  if (y < 0) return -y;
  if (y >= height) return 2 * height - 2 - y;
  return y;
}

constexpr int kStep = 32;

// 16 bytes widened to 16-bit lanes. (Not a lambda: a capture-less lambda's
// function-pointer thunk would not carry the target attribute.)
HOROPTER_AVX2_TARGET inline __m256i widen(const std::uint8_t* p) {
  return _mm256_cvtepu8_epi16(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p)));
}

// Sobel of 16 pixels starting at x (reads x-1 .. x+16 of each row), clamped.
HOROPTER_AVX2_TARGET inline __m256i sobel16(const std::uint8_t* above, const std::uint8_t* here,
                                            const std::uint8_t* below, int x, __m256i lo,
                                            __m256i hi) {
  const __m256i a = _mm256_sub_epi16(widen(above + x + 1), widen(above + x - 1));
  const __m256i h = _mm256_sub_epi16(widen(here + x + 1), widen(here + x - 1));
  const __m256i b = _mm256_sub_epi16(widen(below + x + 1), widen(below + x - 1));
  const __m256i sobel = _mm256_add_epi16(_mm256_add_epi16(a, b), _mm256_add_epi16(h, h));
  return _mm256_min_epi16(_mm256_max_epi16(sobel, lo), hi);
}

// Packs two vectors of 16 values in 0..255 into 32 bytes in pixel order.
HOROPTER_AVX2_TARGET inline __m256i packBytes(__m256i first, __m256i second) {
  return _mm256_permute4x64_epi64(_mm256_packus_epi16(first, second), 0xD8);
}

HOROPTER_AVX2_TARGET void scalarPixel(const std::uint8_t* above, const std::uint8_t* here,
                                      const std::uint8_t* below, int x, int width, int cap,
                                      std::uint8_t* outFiltered, std::uint8_t* outTexture) {
  int sobel = 0;
  if (x > 0 && x < width - 1) {
    sobel = (above[x + 1] - above[x - 1]) + 2 * (here[x + 1] - here[x - 1]) +
            (below[x + 1] - below[x - 1]);
  }
  const int clipped = std::clamp(sobel, -cap, cap);
  if (outFiltered) outFiltered[x] = static_cast<std::uint8_t>(clipped + cap);
  if (outTexture) outTexture[x] = static_cast<std::uint8_t>(std::abs(clipped));
}

}  // namespace

HOROPTER_AVX2_TARGET void prefilterXSobel(const ConstImageView& src, int cap,
                                          const ImageView& filtered, const ImageView& texture,
                                          RowRange rows) {
  const int width = src.width;
  const int height = src.height;
  const __m256i lo = _mm256_set1_epi16(static_cast<std::int16_t>(-cap));
  const __m256i hi = _mm256_set1_epi16(static_cast<std::int16_t>(cap));
  for (int y = rows.begin; y < rows.end; ++y) {
    const auto* above = src.row<std::uint8_t>(reflect101(y - 1, height));
    const auto* here = src.row<std::uint8_t>(y);
    const auto* below = src.row<std::uint8_t>(reflect101(y + 1, height));
    auto* outFiltered = filtered.empty() ? nullptr : filtered.row<std::uint8_t>(y);
    auto* outTexture = texture.empty() ? nullptr : texture.row<std::uint8_t>(y);
    if (width < kStep + 2) {
      for (int x = 0; x < width; ++x)
        scalarPixel(above, here, below, x, width, cap, outFiltered, outTexture);
      continue;
    }
    scalarPixel(above, here, below, 0, width, cap, outFiltered, outTexture);
    scalarPixel(above, here, below, width - 1, width, cap, outFiltered, outTexture);
    // Steps cover [1, width - 1); the last one starts at width - 1 - kStep.
    const int lastStep = width - 1 - kStep;
    for (int x = 1;; x += kStep) {
      x = std::min(x, lastStep);
      const __m256i c0 = sobel16(above, here, below, x, lo, hi);
      const __m256i c1 = sobel16(above, here, below, x + 16, lo, hi);
      if (outFiltered) {
        const __m256i f = packBytes(_mm256_add_epi16(c0, hi), _mm256_add_epi16(c1, hi));
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(outFiltered + x), f);
      }
      if (outTexture) {
        const __m256i t = packBytes(_mm256_abs_epi16(c0), _mm256_abs_epi16(c1));
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(outTexture + x), t);
      }
      if (x == lastStep) break;
    }
  }
}

}  // namespace horopter::avx2
