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

}  // namespace horopter::synth
