// Texture sampling, inline so that the rasteriser's pixel loops can inline
// it (included by textures.hpp; see Texture there).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace horopter::synth {

namespace texture_detail {

// Texture coordinates stay far inside the int range: scenes are metres wide
// and textures a few hundred texels per metre.
inline int fastFloor(double v) {
  const int i = static_cast<int>(v);
  return v < i ? i - 1 : i;
}

// log2 within 0.09 without a library call: the exponent plus the mantissa's
// linear part; plenty to choose a mipmap level (monotonic and continuous).
inline double fastLog2(double v) {
  int e = 0;
  std::uint64_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  e = static_cast<int>((bits >> 52) & 0x7FF) - 1023;
  bits = (bits & 0x000FFFFFFFFFFFFFull) | 0x3FF0000000000000ull;  // mantissa in [1, 2)
  double m;
  std::memcpy(&m, &bits, sizeof m);
  return e + (m - 1);
}

// floor(u), floor(v) and the float fractions u - floor(u), v - floor(v):
// fastFloor's operations (truncate; one less where that is above), and
// with SSE2 the same ones for u and v at once, lane by lane.
inline void floorPair(double u, double v, int& iu, int& iv, float& fu, float& fv) {
#if defined(__SSE2__)
  const __m128d t = _mm_setr_pd(u, v);
  __m128i i = _mm_cvttpd_epi32(t);  // [trunc u, trunc v, 0, 0]
  const __m128d above = _mm_cmplt_pd(t, _mm_cvtepi32_pd(i));
  // Each 64-bit compare lane (all ones: -1) onto its 32-bit index lane.
  i = _mm_add_epi32(i, _mm_shuffle_epi32(_mm_castpd_si128(above), _MM_SHUFFLE(3, 3, 2, 0)));
  const __m128 f = _mm_cvtpd_ps(_mm_sub_pd(t, _mm_cvtepi32_pd(i)));
  iu = _mm_cvtsi128_si32(i);
  iv = _mm_cvtsi128_si32(_mm_shuffle_epi32(i, _MM_SHUFFLE(1, 1, 1, 1)));
  fu = _mm_cvtss_f32(f);
  fv = _mm_cvtss_f32(_mm_shuffle_ps(f, f, _MM_SHUFFLE(1, 1, 1, 1)));
#else
  iu = fastFloor(u);
  iv = fastFloor(v);
  fu = static_cast<float>(u - iu);
  fv = static_cast<float>(v - iv);
#endif
}

inline int wrapIndex(int i, int n) {
  const int r = i % n;
  return r < 0 ? r + n : r;
}

#if defined(__SSE2__)
// The three floats of a texel in lanes 0-2 (lane 3: 0), reading no further.
inline __m128 loadTexel(const float* p) {
  // _mm_loadu_si64 makes no alignment promise; a texel starts at any multiple of 4 bytes.
  const __m128 xy = _mm_castsi128_ps(_mm_loadu_si64(p));
  return _mm_movelh_ps(xy, _mm_load_ss(p + 2));
}

inline cv::Vec3f toVec3f(__m128 v) {
  alignas(16) float t[4];
  _mm_store_ps(t, v);
  return {t[0], t[1], t[2]};
}
#else
inline cv::Vec3f toVec3f(const cv::Vec3f& v) {
  return v;
}
#endif

}  // namespace texture_detail

template <bool Wrap>
[[gnu::always_inline]] inline Texture::Texel Texture::sampleLevel(int level, double u,
                                                                  double v) const {
  const LevelView& img = views_[static_cast<std::size_t>(level)];
  // Texel centres sit at integer coordinates of each level.
  u = u * img.scale - 0.5;
  v = v * img.scale - 0.5;
  const int w = img.w, h = img.h;
  int x0, y0, x1, y1;
  float fx, fy;
  if constexpr (Wrap) {
    // floor without a libm call (no SSE4.1 in the baseline build)
    int iu, iv;
    texture_detail::floorPair(u, v, iu, iv, fx, fy);
    if (img.wrapByMask) {
      // Power-of-two sides (two's complement): the neighbour wraps by the mask too.
      x0 = iu & img.wMask;
      y0 = iv & img.hMask;
      x1 = static_cast<int>((static_cast<unsigned>(iu) + 1) & static_cast<unsigned>(img.wMask));
      y1 = static_cast<int>((static_cast<unsigned>(iv) + 1) & static_cast<unsigned>(img.hMask));
    } else {
      x0 = texture_detail::wrapIndex(iu, w);
      y0 = texture_detail::wrapIndex(iv, h);
      x1 = x0 + 1 == w ? 0 : x0 + 1;
      y1 = y0 + 1 == h ? 0 : y0 + 1;
    }
  } else {
    u = std::clamp(u, 0.0, w - 1.0);
    v = std::clamp(v, 0.0, h - 1.0);
    x0 = static_cast<int>(u);
    y0 = static_cast<int>(v);
    x1 = std::min(x0 + 1, w - 1);
    y1 = std::min(y0 + 1, h - 1);
    fx = static_cast<float>(u - x0);
    fy = static_cast<float>(v - y0);
  }
  // Bilinear, channel by channel in plain floats (the same operations as
  // cv::Vec3f's, which the compiler did not keep in registers).
  // The indices are never negative: through unsigned, the offsets need no
  // sign extension.
  const auto offset = [](int i) { return static_cast<std::size_t>(static_cast<unsigned>(i)); };
  const float* row0 = img.data + offset(y0) * img.rowFloats;
  const float* row1 = img.data + offset(y1) * img.rowFloats;
  const std::size_t ox0 = 3 * offset(x0), ox1 = 3 * offset(x1);
  const float* a = row0 + ox0;
  const float* b = row0 + ox1;
  const float* c = row1 + ox0;
  const float* d = row1 + ox1;
  const float gx = 1 - fx, gy = 1 - fy;
#if defined(__SSE2__)
  // The three channels at once: the same float operations, lane by lane.
  using texture_detail::loadTexel;
  const __m128 vgx = _mm_set1_ps(gx), vfx = _mm_set1_ps(fx);
  const __m128 top = _mm_add_ps(_mm_mul_ps(loadTexel(a), vgx), _mm_mul_ps(loadTexel(b), vfx));
  const __m128 bottom = _mm_add_ps(_mm_mul_ps(loadTexel(c), vgx), _mm_mul_ps(loadTexel(d), vfx));
  return _mm_add_ps(_mm_mul_ps(top, _mm_set1_ps(gy)), _mm_mul_ps(bottom, _mm_set1_ps(fy)));
#else
  cv::Vec3f out;
  for (int k = 0; k < 3; ++k) {
    const float top = a[k] * gx + b[k] * fx;
    const float bottom = c[k] * gx + d[k] * fx;
    out[k] = top * gy + bottom * fy;
  }
  return out;
#endif
}

template <bool Wrap>
[[gnu::always_inline]] inline Texture::Texel Texture::sample(double u, double v,
                                                             double footprint) const {
  const double lod = footprint > 1 ? texture_detail::fastLog2(footprint) : 0.0;
  if (lod <= 0) return sampleLevel<Wrap>(0, u, v);
  if (lod >= lastLevelLod_) return sampleLevel<Wrap>(lastLevel_, u, v);
  const int l0 = static_cast<int>(lod);
  const float f = static_cast<float>(lod - l0);
  const Texel a = sampleLevel<Wrap>(l0, u, v), b = sampleLevel<Wrap>(l0 + 1, u, v);
  const float g = 1 - f;
#if defined(__SSE2__)
  return _mm_add_ps(_mm_mul_ps(a, _mm_set1_ps(g)), _mm_mul_ps(b, _mm_set1_ps(f)));
#else
  return cv::Vec3f(a[0] * g + b[0] * f, a[1] * g + b[1] * f, a[2] * g + b[2] * f);
#endif
}

inline Texture::Texel Texture::sampleWrapTexel(double u, double v, double footprint) const {
  return sample<true>(u, v, footprint);
}

inline Texture::Texel Texture::sampleClampTexel(double u, double v, double footprint) const {
  return sample<false>(u, v, footprint);
}

inline cv::Vec3f Texture::sampleWrap(double u, double v, double footprint) const {
  return texture_detail::toVec3f(sample<true>(u, v, footprint));
}

inline cv::Vec3f Texture::sampleClamp(double u, double v, double footprint) const {
  return texture_detail::toVec3f(sample<false>(u, v, footprint));
}

}  // namespace horopter::synth
