// 16-bit lane transposes shared by the AVX2 matcher's region sweep
// (sad_avx2.cpp) and its left band (sad_band_avx2.cpp). Include only from
// AVX2 translation units: every function carries the AVX2 target.
#pragma once

#include <immintrin.h>

#include "common/cpu_features.hpp"

namespace horopter::avx2 {

// Half of transpose16: 8 vectors r[0..7] (pixels j, 16 lanes each) become
// w[c], c = 0..7, whose low 128 bits hold lane c of the 8 pixels and whose
// high 128 bits lane c + 8. Stored as 128-bit halves, they need no lane
// exchange, and a block of 16 pixels needs only 8 of its cost vectors live.
[[gnu::always_inline]] HOROPTER_AVX2_TARGET inline void transpose8x16(const __m256i* r,
                                                                      __m256i* w) {
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
    w[2 * m] = _mm256_unpacklo_epi64(u[m], u[m + 4]);
    w[2 * m + 1] = _mm256_unpackhi_epi64(u[m], u[m + 4]);
  }
}

// Transposes 16 vectors of 16 lanes: t[k] lane j = v[j] lane k. Each half of
// 8 rows is transpose8x16 (three unpack stages within 128-bit lanes); a
// 128-bit lane exchange joins the halves.
[[gnu::always_inline]] HOROPTER_AVX2_TARGET inline void transpose16(const __m256i* v, __m256i* t) {
  __m256i w[2][8];
  transpose8x16(v, w[0]);
  transpose8x16(v + 8, w[1]);
  for (int c = 0; c < 8; ++c) {
    t[c] = _mm256_permute2x128_si256(w[0][c], w[1][c], 0x20);
    t[c + 8] = _mm256_permute2x128_si256(w[0][c], w[1][c], 0x31);
  }
}

}  // namespace horopter::avx2
