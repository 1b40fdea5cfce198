// AVX2 horopter mask: bit-exact with the scalar reference.
//
// Strategy
//   Lanes: 32 pixels per step, as two vectors of 16 int16 disparities and
//   thresholds. outside = (d == v) | (T > d) in 16-bit lanes; its complement
//   packed to bytes (packs, then a cross-lane permute) is the 0/255 mask.
//   Segmented U8C1 is mask & image. Segmented U8C3 needs each mask byte three
//   times (96 bytes per step): three byte shuffles (pshufb works within
//   128-bit halves, so each takes its source half broadcast or in place)
//   expand the mask, which is then ANDed with the image.
//   Tails: a row of at least 32 pixels ends with one step placed flush
//   against the row end, overlapping the previous one (it rewrites the same
//   values and touches nothing outside the row); narrower rows take the
//   scalar formula.
#include <immintrin.h>

#include <algorithm>
#include <cstdint>

#include "common/cpu_features.hpp"
#include "horopter_mask/horopter_mask.hpp"

namespace horopter::avx2 {

namespace {

constexpr int kStep = 32;

HOROPTER_AVX2_TARGET inline __m256i load(const void* p) {
  return _mm256_loadu_si256(static_cast<const __m256i*>(p));
}
HOROPTER_AVX2_TARGET inline void store(void* p, __m256i v) {
  _mm256_storeu_si256(static_cast<__m256i*>(p), v);
}

// 0xFF where pixel x + i is inside, for i in 0..31.
HOROPTER_AVX2_TARGET inline __m256i maskStep(const std::int16_t* d, const std::int16_t* t, int x,
                                             __m256i invalid) {
  auto outside = [&](int at) HOROPTER_AVX2_TARGET {
    const __m256i dv = load(d + at);
    return _mm256_or_si256(_mm256_cmpeq_epi16(dv, invalid), _mm256_cmpgt_epi16(load(t + at), dv));
  };
  const __m256i out =
      _mm256_permute4x64_epi64(_mm256_packs_epi16(outside(x), outside(x + 16)), 0xD8);
  return _mm256_xor_si256(out, _mm256_set1_epi8(-1));
}

// Byte indices i / 3 (minus the start of the source half) for output bytes of
// a 96-byte U8C3 step: bytes [0, 32) read the mask's low half in both lanes,
// [32, 64) the mask as is, [64, 96) its high half in both lanes.
struct Expand3 {
  __m256i first, second, third;
};

HOROPTER_AVX2_TARGET Expand3 expand3Indices() {
  alignas(32) std::int8_t idx[3][32];
  for (int j = 0; j < 32; ++j) {
    idx[0][j] = static_cast<std::int8_t>(j / 3);
    idx[1][j] = static_cast<std::int8_t>((32 + j) / 3 - (j < 16 ? 0 : 16));
    idx[2][j] = static_cast<std::int8_t>((64 + j) / 3 - 16);
  }
  return {load(idx[0]), load(idx[1]), load(idx[2])};
}

HOROPTER_AVX2_TARGET void scalarRow(const std::int16_t* d, std::span<const std::int16_t> thresholds,
                                    std::int16_t invalid, std::uint8_t* m, const std::uint8_t* in,
                                    std::uint8_t* out, int width, int channels) {
  for (int x = 0; x < width; ++x) {
    const bool inside = d[x] != invalid && d[x] >= thresholds[x];
    m[x] = inside ? 255 : 0;
    for (int c = 0; c < channels; ++c)
      out[x * channels + c] = inside ? in[x * channels + c] : 0;
  }
}

}  // namespace

HOROPTER_AVX2_TARGET void horopterMask(const ConstImageView& disparity,
                                       std::span<const std::int16_t> thresholds,
                                       std::int16_t invalid, const ImageView& mask,
                                       const ConstImageView& image, const ImageView& segmented,
                                       RowRange rows) {
  const int width = disparity.width;
  const int channels = segmented.empty() ? 0 : static_cast<int>(pixelBytes(image.type));
  const __m256i invalidV = _mm256_set1_epi16(invalid);
  const Expand3 e3 = expand3Indices();
  const std::int16_t* t = thresholds.data();
  for (int y = rows.begin; y < rows.end; ++y) {
    const auto* d = disparity.row<std::int16_t>(y);
    auto* m = mask.row<std::uint8_t>(y);
    const auto* in = channels ? image.row<std::uint8_t>(y) : nullptr;
    auto* out = channels ? segmented.row<std::uint8_t>(y) : nullptr;
    if (width < kStep) {
      scalarRow(d, thresholds, invalid, m, in, out, width, channels);
      continue;
    }
    for (int x = 0;; x += kStep) {
      x = std::min(x, width - kStep);
      const __m256i inside = maskStep(d, t, x, invalidV);
      store(m + x, inside);
      if (channels == 1) {
        store(out + x, _mm256_and_si256(inside, load(in + x)));
      } else if (channels == 3) {
        const __m256i low = _mm256_broadcastsi128_si256(_mm256_castsi256_si128(inside));
        const __m256i high = _mm256_broadcastsi128_si256(_mm256_extracti128_si256(inside, 1));
        const std::uint8_t* src = in + 3 * x;
        std::uint8_t* dst = out + 3 * x;
        store(dst, _mm256_and_si256(_mm256_shuffle_epi8(low, e3.first), load(src)));
        store(dst + 32, _mm256_and_si256(_mm256_shuffle_epi8(inside, e3.second), load(src + 32)));
        store(dst + 64, _mm256_and_si256(_mm256_shuffle_epi8(high, e3.third), load(src + 64)));
      }
      if (x == width - kStep) break;
    }
  }
}

}  // namespace horopter::avx2
