// Ray intersections and shading of the scene's shapes; see primitives.hpp.
#include "synthetic/primitives.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace horopter::synth {

namespace {

constexpr double kTMin = 1e-6;

double comp(const Vec3& v, int axis) {
  return axis == 0 ? v.x : axis == 1 ? v.y : v.z;
}

// Surface coordinates on a box face: the two other axes, in metres from the
// box's min corner (u along x for the y and z faces, along z for the x faces).
void boxFaceUV(const Primitive& p, const Vec3& q, int axis, Hit& hit) {
  const Vec3 rel = q - p.a;
  const Vec3 size = p.b - p.a;
  double u = 0, v = 0, su = 1, sv = 1;
  if (axis == 0) {
    u = rel.z, v = rel.y, su = size.z, sv = size.y;
  } else if (axis == 1) {
    u = rel.x, v = rel.z, su = size.x, sv = size.z;
  } else {
    u = rel.x, v = rel.y, su = size.x, sv = size.y;
  }
  if (p.materials[hit.face].mapping == Material::Mapping::Stretch) {
    u /= su;
    v /= sv;
  }
  hit.u = u;
  hit.v = v;
}

bool intersectBox(const Primitive& p, const Ray& ray, double tMax, Hit& hit) {
  double tNear = -std::numeric_limits<double>::infinity();
  double tFar = std::numeric_limits<double>::infinity();
  int nearAxis = 0;
  bool nearMax = false;
  for (int axis = 0; axis < 3; ++axis) {
    const double o = comp(ray.o, axis), d = comp(ray.d, axis);
    const double lo = comp(p.a, axis), hi = comp(p.b, axis);
    if (d == 0) {
      if (o < lo || o > hi) return false;
      continue;
    }
    double t0 = (lo - o) / d, t1 = (hi - o) / d;
    bool enterMax = false;
    if (t0 > t1) {
      std::swap(t0, t1);
      enterMax = true;
    }
    if (t0 > tNear) {
      tNear = t0;
      nearAxis = axis;
      nearMax = enterMax;
    }
    tFar = std::min(tFar, t1);
  }
  if (!(tNear <= tFar) || tNear <= kTMin || tNear >= tMax) return false;
  hit.t = tNear;
  hit.face = 2 * nearAxis + (nearMax ? 1 : 0);
  Vec3 n;
  (nearAxis == 0 ? n.x : nearAxis == 1 ? n.y : n.z) = nearMax ? 1 : -1;
  hit.normal = n;
  boxFaceUV(p, ray.o + hit.t * ray.d, nearAxis, hit);
  return true;
}

// The room seen from inside: the ray leaves through the nearest exit plane.
bool intersectRoom(const Primitive& p, const Ray& ray, double tMax, Hit& hit) {
  double tExit = std::numeric_limits<double>::infinity();
  int exitAxis = -1;
  bool exitMax = false;
  for (int axis = 0; axis < 3; ++axis) {
    const double d = comp(ray.d, axis);
    if (d == 0) continue;
    const bool toMax = d > 0;
    const double t = ((toMax ? comp(p.b, axis) : comp(p.a, axis)) - comp(ray.o, axis)) / d;
    if (t < tExit) {
      tExit = t;
      exitAxis = axis;
      exitMax = toMax;
    }
  }
  if (exitAxis < 0 || tExit <= kTMin || tExit >= tMax) return false;
  hit.t = tExit;
  hit.face = 2 * exitAxis + (exitMax ? 1 : 0);
  Vec3 n;  // facing into the room
  (exitAxis == 0 ? n.x : exitAxis == 1 ? n.y : n.z) = exitMax ? -1 : 1;
  hit.normal = n;
  boxFaceUV(p, ray.o + hit.t * ray.d, exitAxis, hit);
  return true;
}

bool intersectEllipsoid(const Primitive& p, const Ray& ray, double tMax, Hit& hit) {
  // In the unit-sphere space of the ellipsoid, with the ray's own t.
  const Vec3 ol = p.orient.applyInverse(ray.o - p.a);
  const Vec3 dl = p.orient.applyInverse(ray.d);
  const Vec3 os{ol.x / p.radii.x, ol.y / p.radii.y, ol.z / p.radii.z};
  const Vec3 ds{dl.x / p.radii.x, dl.y / p.radii.y, dl.z / p.radii.z};
  const double a = dot(ds, ds), b = dot(os, ds), c = dot(os, os) - 1;
  const double disc = b * b - a * c;
  if (disc < 0) return false;
  const double t = (-b - std::sqrt(disc)) / a;
  if (t <= kTMin || t >= tMax) return false;
  hit.t = t;
  const Vec3 q = ol + t * dl;  // local hit point
  const Vec3 nl{q.x / (p.radii.x * p.radii.x), q.y / (p.radii.y * p.radii.y),
                q.z / (p.radii.z * p.radii.z)};
  hit.normal = normalized(p.orient.apply(nl));
  hit.face = 0;
  if (p.materials[0].mapping == Material::Mapping::Face) {
    // Orthographic from the front: the photograph's left column lies on the
    // person's right (local +x), which the viewer facing them sees on the left.
    hit.u = 0.5 - 0.5 * q.x / p.radii.x;
    hit.v = 0.5 + 0.5 * q.y / p.radii.y;
    hit.back = q.z < 0;
  } else {
    hit.u = q.x - q.z;
    hit.v = q.y;
  }
  return true;
}

bool intersectCapsule(const Primitive& p, const Ray& ray, double tMax, Hit& hit) {
  // Inigo Quilez's capsule intersection, with the unit direction dn; s is
  // the distance along dn, t = s / |d|.
  const Vec3 ba = p.b - p.a, oa = ray.o - p.a;
  const double r = p.radius;
  const double baba = dot(ba, ba), bard = dot(ba, ray.dn), baoa = dot(ba, oa);
  const double rdoa = dot(ray.dn, oa), oaoa = dot(oa, oa);
  const double a = baba - bard * bard;
  double s = -1;
  Vec3 axisPoint;
  if (a > 1e-12) {
    const double b = baba * rdoa - baoa * bard;
    const double c = baba * oaoa - baoa * baoa - r * r * baba;
    const double h = b * b - a * c;
    if (h < 0) return false;
    const double sb = (-b - std::sqrt(h)) / a;
    const double y = baoa + sb * bard;
    if (y > 0 && y < baba) {
      s = sb;
      axisPoint = p.a + (y / baba) * ba;
    }
  }
  if (s < 0) {
    // The caps: the nearer hit on the two end spheres.
    double best = std::numeric_limits<double>::infinity();
    for (const Vec3& cc : {p.a, p.b}) {
      const Vec3 oc = ray.o - cc;
      const double b = dot(ray.dn, oc), c = dot(oc, oc) - r * r;
      const double h = b * b - c;
      if (h < 0) continue;
      const double sc = -b - std::sqrt(h);
      if (sc > 0 && sc < best) {
        best = sc;
        axisPoint = cc;
      }
    }
    if (!std::isfinite(best)) return false;
    s = best;
  }
  const double t = s / ray.length;
  if (t <= kTMin || t >= tMax) return false;
  hit.t = t;
  const Vec3 q = ray.o + s * ray.dn;
  hit.normal = (1.0 / r) * (q - axisPoint);
  hit.face = 0;
  // Around the axis (arc length) and along it, in metres.
  const Vec3 axis = (1.0 / std::sqrt(baba)) * ba;
  const Vec3 helper = std::abs(axis.y) < 0.9 ? Vec3{0, 1, 0} : Vec3{1, 0, 0};
  const Vec3 e1 = normalized(cross(axis, helper)), e2 = cross(axis, e1);
  hit.u = r * std::atan2(dot(hit.normal, e2), dot(hit.normal, e1));
  hit.v = dot(q - p.a, axis);
  return true;
}

}  // namespace

void Primitive::bounds(Vec3& lo, Vec3& hi) const {
  switch (shape) {
    case Shape::Box:
    case Shape::Room:
      lo = a, hi = b;
      return;
    case Shape::Ellipsoid: {
      const double r = std::max({radii.x, radii.y, radii.z});
      lo = a - Vec3{r, r, r}, hi = a + Vec3{r, r, r};
      return;
    }
    case Shape::Capsule:
      lo = {std::min(a.x, b.x) - radius, std::min(a.y, b.y) - radius, std::min(a.z, b.z) - radius};
      hi = {std::max(a.x, b.x) + radius, std::max(a.y, b.y) + radius, std::max(a.z, b.z) + radius};
      return;
  }
}

Primitive makeBox(Vec3 lo, Vec3 hi, const Material& material) {
  Primitive p;
  p.shape = Primitive::Shape::Box;
  p.a = lo, p.b = hi;
  for (Material& m : p.materials)
    m = material;
  return p;
}

Primitive makeEllipsoid(Vec3 centre, Vec3 radii, double yaw, const Material& material) {
  Primitive p;
  p.shape = Primitive::Shape::Ellipsoid;
  p.a = centre;
  p.radii = radii;
  p.orient = rotationY(yaw);
  p.materials[0] = material;
  return p;
}

Primitive makeCapsule(Vec3 a, Vec3 b, double radius, const Material& material) {
  Primitive p;
  p.shape = Primitive::Shape::Capsule;
  p.a = a, p.b = b;
  p.radius = radius;
  p.materials[0] = material;
  return p;
}

bool intersect(const Primitive& p, const Ray& ray, double tMax, Hit& hit) {
  switch (p.shape) {
    case Primitive::Shape::Box:
      return intersectBox(p, ray, tMax, hit);
    case Primitive::Shape::Room:
      return intersectRoom(p, ray, tMax, hit);
    case Primitive::Shape::Ellipsoid:
      return intersectEllipsoid(p, ray, tMax, hit);
    case Primitive::Shape::Capsule:
      return intersectCapsule(p, ray, tMax, hit);
  }
  return false;
}

cv::Vec3f shade(const Primitive& p, const Ray& ray, const Hit& hit, double pixelMetres) {
  const Material& m = p.materials[hit.face];
  // Light from above, behind the robot and to its left (y is down).
  static const Vec3 kToLight = normalized(Vec3{-0.35, -0.8, -0.5});
  const double lambert = std::max(0.0, dot(hit.normal, kToLight));
  const float light = static_cast<float>(0.55 + 0.55 * lambert);
  // Metres covered by one pixel at this depth (ignoring slant).
  const double footprintM = hit.t * pixelMetres;
  const Texture& tex = texture(m.texture);
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
  (void)ray;
  return cv::Vec3f(c[0] * m.gain[0], c[1] * m.gain[1], c[2] * m.gain[2]) * light;
}

}  // namespace horopter::synth
