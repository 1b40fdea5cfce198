// The exact ray tests of each shape, inline so that the rasteriser's pixel
// loops (one per shape) can inline them; see primitives.hpp for the contract.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "synthetic/primitives.hpp"

namespace horopter::synth::detail {

inline constexpr double kTMin = 1e-6;

inline double comp(const Vec3& v, int axis) {
  return axis == 0 ? v.x : axis == 1 ? v.y : v.z;
}

// Surface coordinates on a box face: the two other axes, in metres from the
// box's min corner (u along x for the y and z faces, along z for the x faces).
inline void boxFaceUV(const Primitive& p, const Vec3& q, int axis, Hit& hit) {
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

inline bool intersectBox(const Primitive& p, const Ray& ray, double tMax, Hit& hit) {
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
inline bool intersectRoom(const Primitive& p, const Ray& ray, double tMax, Hit& hit) {
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

inline bool intersectEllipsoid(const Primitive& p, const Ray& ray, double tMax, Hit& hit) {
  // In the unit-sphere space of the ellipsoid, with the ray's own t; the
  // origin's image (preVec) and its |.|^2 - 1 (pre0) come from prepare().
  const Vec3 dl = p.orient.applyInverse(ray.d);
  const Vec3& os = p.preVec;
  const Vec3 ds{dl.x * p.pre1, dl.y * p.pre2, dl.z / p.radii.z};
  const double a = dot(ds, ds), b = dot(os, ds), c = p.pre0;
  const double disc = b * b - a * c;
  if (disc < 0) return false;
  const double t = (-b - std::sqrt(disc)) / a;
  if (t <= kTMin || t >= tMax) return false;
  hit.t = t;
  const Vec3 q = p.orient.applyInverse(ray.o - p.a) + t * dl;  // local hit point
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

// atan2 to about 1e-4 rad without a libm call; any smooth, deterministic
// function of the surface point would do for texture coordinates.
inline double fastAtan2(double y, double x) {
  const double ax = std::abs(x), ay = std::abs(y);
  const double mx = std::max(ax, ay);
  if (mx == 0) return 0;
  const double a = std::min(ax, ay) / mx;
  const double s = a * a;
  double r = ((-0.0464964749 * s + 0.15931422) * s - 0.327622764) * s * a + a;
  if (ay > ax) r = 1.57079637 - r;
  if (x < 0) r = 3.14159265 - r;
  return y < 0 ? -r : r;
}

inline bool intersectCapsule(const Primitive& p, const Ray& ray, double tMax, Hit& hit) {
  // Inigo Quilez's capsule intersection, for a direction d of any length.
  // oa (preVec), ba.oa (pre0), oa.oa (pre1), ba.ba (pre2), the axis and
  // the vectors across it from prepare().
  const Vec3 ba = p.b - p.a, oa = p.preVec;
  const double r = p.radius;
  const double baba = p.pre2, bard = dot(ba, ray.d), baoa = p.pre0;
  const double rdoa = dot(ray.d, oa), oaoa = p.pre1, dd = dot(ray.d, ray.d);
  const double a = baba * dd - bard * bard;
  double t = -1;
  Vec3 axisPoint;
  if (a > 1e-12 * baba * dd) {
    const double b = baba * rdoa - baoa * bard;
    const double c = baba * oaoa - baoa * baoa - r * r * baba;
    const double h = b * b - a * c;
    if (h < 0) return false;  // misses the infinite cylinder, so the caps too
    const double tb = (-b - std::sqrt(h)) / a;
    const double y = baoa + tb * bard;
    if (y > 0 && y < baba) {
      t = tb;
      axisPoint = p.a + (y / baba) * ba;
    }
  }
  if (t < 0) {
    // The caps: the nearer hit on the two end spheres.
    double best = std::numeric_limits<double>::infinity();
    for (const Vec3& cc : {p.a, p.b}) {
      const Vec3 oc = ray.o - cc;
      const double b = dot(ray.d, oc), c = dot(oc, oc) - r * r;
      const double h = b * b - dd * c;
      if (h < 0) continue;
      const double tc = (-b - std::sqrt(h)) / dd;
      if (tc > 0 && tc < best) {
        best = tc;
        axisPoint = cc;
      }
    }
    if (!std::isfinite(best)) return false;
    t = best;
  }
  if (t <= kTMin || t >= tMax) return false;
  hit.t = t;
  const Vec3 q = ray.o + t * ray.d;
  hit.normal = p.invRadius * (q - axisPoint);
  hit.face = 0;
  // Around the axis (arc length) and along it, in metres.
  hit.u = r * fastAtan2(dot(hit.normal, p.across2), dot(hit.normal, p.across1));
  hit.v = dot(q - p.a, p.axis);
  return true;
}

}  // namespace horopter::synth::detail
