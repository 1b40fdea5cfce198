// The colour of a hit, inline so that the rasteriser's pixel loops can
// inline it; see primitives.hpp for the shapes and hits.
#pragma once

#include <algorithm>

#include "synthetic/primitives.hpp"
#include "synthetic/textures.hpp"

namespace horopter::synth {

// Light from above, behind the robot and to its left (y is down); at
// namespace scope so that shade() does not test a guard per pixel.
inline const Vec3 kToLight = normalized(Vec3{-0.35, -0.8, -0.5});

// The colour (BGR floats) of a hit, lit by a fixed directional light; the
// lighting depends on the surface only, never on the viewpoint (nor on the
// ray), so both views see the same colour at the same surface point.
// `tex`: texture(m.texture) of the hit's material m (looked up once per
// primitive by the caller); `pixelMetres`: the size of a pixel's footprint
// at unit depth (1 / f).
inline cv::Vec3f shade(const Primitive& p, const Hit& hit, const Texture& tex, double pixelMetres) {
  const Material& m = p.materials[hit.face];
  const double lambert = std::max(0.0, dot(hit.normal, kToLight));
  const float light = static_cast<float>(0.55 + 0.55 * lambert);
  // Metres covered by one pixel at this depth (ignoring slant).
  const double footprintM = hit.t * pixelMetres;
  cv::Vec3f c;
  switch (m.mapping) {
    case Material::Mapping::Tiled:
      c = tex.sampleWrap(hit.u * m.texelsPerMetre, hit.v * m.texelsPerMetre,
                         footprintM * m.texelsPerMetre);
      break;
    case Material::Mapping::Stretch:
      c = tex.sampleClamp(hit.u * tex.width(), hit.v * tex.height(), footprintM * m.texelsPerMetre);
      break;
    case Material::Mapping::Face:
      if (hit.back) return m.gain * light;
      c = tex.sampleClamp(hit.u * tex.width(), hit.v * tex.height(), footprintM * m.texelsPerMetre);
      return c * light;
  }
  return cv::Vec3f(c[0] * m.gain[0], c[1] * m.gain[1], c[2] * m.gain[2]) * light;
}

// shade() as a pixel: each channel rounded to the nearest and saturated, as
// cv::saturate_cast<uchar> does. With SSE2 the three channels take the same
// float operations as shade()'s, lane by lane, and the rounding is the same
// instruction's (cvtps2dq as cvRound's cvtss2si), so the bytes are the same.
inline cv::Vec3b shadePixel(const Primitive& p, const Hit& hit, const Texture& tex,
                            double pixelMetres) {
#if defined(__SSE2__)
  const Material& m = p.materials[hit.face];
  const double lambert = std::max(0.0, dot(hit.normal, kToLight));
  const __m128 light = _mm_set1_ps(static_cast<float>(0.55 + 0.55 * lambert));
  const double footprintM = hit.t * pixelMetres;
  const __m128 gain = _mm_setr_ps(m.gain[0], m.gain[1], m.gain[2], 0.0f);
  __m128 c = _mm_setzero_ps();
  switch (m.mapping) {
    case Material::Mapping::Tiled:
      c = tex.sampleWrapTexel(hit.u * m.texelsPerMetre, hit.v * m.texelsPerMetre,
                              footprintM * m.texelsPerMetre);
      c = _mm_mul_ps(_mm_mul_ps(c, gain), light);
      break;
    case Material::Mapping::Stretch:
      c = tex.sampleClampTexel(hit.u * tex.width(), hit.v * tex.height(),
                               footprintM * m.texelsPerMetre);
      c = _mm_mul_ps(_mm_mul_ps(c, gain), light);
      break;
    case Material::Mapping::Face:
      if (hit.back) {
        c = _mm_mul_ps(gain, light);
      } else {
        c = tex.sampleClampTexel(hit.u * tex.width(), hit.v * tex.height(),
                                 footprintM * m.texelsPerMetre);
        c = _mm_mul_ps(c, light);
      }
      break;
  }
  __m128i i = _mm_cvtps_epi32(c);
  i = _mm_packs_epi32(i, i);   // saturated to int16,
  i = _mm_packus_epi16(i, i);  // then to 0..255
  const int bgr = _mm_cvtsi128_si32(i);
  return cv::Vec3b(static_cast<uchar>(bgr), static_cast<uchar>(bgr >> 8),
                   static_cast<uchar>(bgr >> 16));
#else
  const cv::Vec3f c = shade(p, hit, tex, pixelMetres);
  return cv::Vec3b(cv::saturate_cast<uchar>(c[0]), cv::saturate_cast<uchar>(c[1]),
                   cv::saturate_cast<uchar>(c[2]));
#endif
}

}  // namespace horopter::synth
