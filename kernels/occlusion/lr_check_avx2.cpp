// AVX2 lr check: bit-exact with the scalar reference.
//
// Strategy
//   Lanes: 8 pixels per step in 32-bit lanes, where dl = (d + 8) >> 4,
//   xr = x - dl and |dl - WR(xr)| are exact for any int16 input. WR(xr) is
//   fetched with a masked 32-bit gather (only lanes with a valid d and xr in
//   [0, W) load anything). The gather reads the int16 pair (xr - 1, xr) and
//   keeps the high half, so it never reads past the row's last pixel; lanes
//   with xr == 0 (whose pair would start before the row) take WR(0) from a
//   broadcast instead. The resulting 32-bit decision mask is packed to 16-bit
//   lanes and blends the invalid marker into the disparities.
//   Tails: a row of at least 8 pixels ends with one step placed flush against
//   the row end, overlapping the previous one; that is harmless because the
//   check is idempotent per pixel (a pixel it invalidated is skipped, one it
//   kept is kept again) and reads no other disparity. Narrower rows take the
//   scalar loop.
#include <immintrin.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>

#include "common/cpu_features.hpp"
#include "occlusion/occlusion.hpp"

namespace horopter::avx2 {

namespace {

constexpr int kStep = 8;

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

}  // namespace

HOROPTER_AVX2_TARGET void leftRightCheck(const ImageView& disparity,
                                         const ConstImageView& winnerRight,
                                         const StereoParams& params, RowRange rows) {
  if (params.disp12MaxDiff < 0) return;
  const std::int16_t invalid = invalidDisparity(params);
  const int noWinner = params.minDisparity - 1;
  const int width = disparity.width;
  const __m256i invalid32 = _mm256_set1_epi32(invalid);
  const __m128i invalid16 = _mm_set1_epi16(invalid);
  const __m256i noWinnerV = _mm256_set1_epi32(noWinner);
  const __m256i maxDiffV = _mm256_set1_epi32(params.disp12MaxDiff);
  const __m256i widthV = _mm256_set1_epi32(width);
  const __m256i eight = _mm256_set1_epi32(8);
  const __m256i minusOne = _mm256_set1_epi32(-1);
  const __m256i zero = _mm256_setzero_si256();
  const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  for (int y = rows.begin; y < rows.end; ++y) {
    auto* d = disparity.row<std::int16_t>(y);
    const auto* wr = winnerRight.row<std::int16_t>(y);
    if (width < kStep) {
      scalarRow(d, wr, width, invalid, noWinner, params.disp12MaxDiff);
      continue;
    }
    const __m256i wr0 = _mm256_set1_epi32(wr[0]);
    const int* gatherBase = reinterpret_cast<const int*>(wr);
    for (int x = 0;; x += kStep) {
      x = std::min(x, width - kStep);
      auto* at = reinterpret_cast<__m128i*>(d + x);
      const __m128i d16 = _mm_loadu_si128(at);
      const __m256i dv = _mm256_cvtepi16_epi32(d16);
      const __m256i dl = _mm256_srai_epi32(_mm256_add_epi32(dv, eight), 4);
      const __m256i xr = _mm256_sub_epi32(_mm256_add_epi32(_mm256_set1_epi32(x), lane), dl);
      const __m256i valid = _mm256_andnot_si256(_mm256_cmpeq_epi32(dv, invalid32), minusOne);
      // 0 <= xr < width.
      const __m256i inRange =
          _mm256_andnot_si256(_mm256_cmpgt_epi32(zero, xr), _mm256_cmpgt_epi32(widthV, xr));
      const __m256i use = _mm256_and_si256(valid, inRange);
      const __m256i atZero = _mm256_cmpeq_epi32(xr, zero);
      // Pairs (xr - 1, xr) at byte offset 2 * (xr - 1); the high half is WR(xr).
      const __m256i pairs =
          _mm256_mask_i32gather_epi32(zero, gatherBase, _mm256_sub_epi32(xr, _mm256_set1_epi32(1)),
                                      _mm256_andnot_si256(atZero, use), 2);
      const __m256i w = _mm256_blendv_epi8(_mm256_srai_epi32(pairs, 16), wr0, atZero);
      const __m256i hasWinner = _mm256_andnot_si256(_mm256_cmpeq_epi32(w, noWinnerV), use);
      const __m256i tooFar =
          _mm256_cmpgt_epi32(_mm256_abs_epi32(_mm256_sub_epi32(dl, w)), maxDiffV);
      const __m256i reject = _mm256_and_si256(hasWinner, tooFar);
      const __m128i reject16 =
          _mm_packs_epi32(_mm256_castsi256_si128(reject), _mm256_extracti128_si256(reject, 1));
      _mm_storeu_si128(at, _mm_blendv_epi8(d16, invalid16, reject16));
      if (x == width - kStep) break;
    }
  }
}

}  // namespace horopter::avx2
