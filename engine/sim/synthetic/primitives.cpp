// Ray intersections and shading of the scene's shapes; see primitives.hpp.
#include "synthetic/primitives.hpp"

#include "synthetic/intersections.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace horopter::synth {

void Primitive::bounds(Vec3& lo, Vec3& hi) const {
  switch (shape) {
    case Shape::Box:
    case Shape::Room:
      lo = a, hi = b;
      return;
    case Shape::Ellipsoid: {
      // The exact extent of a turned ellipsoid along each world axis.
      auto extent = [&](const Vec3& row) {
        return std::sqrt(row.x * row.x * radii.x * radii.x + row.y * row.y * radii.y * radii.y +
                         row.z * row.z * radii.z * radii.z);
      };
      const Vec3 e{extent(orient.r[0]), extent(orient.r[1]), extent(orient.r[2])};
      lo = a - e, hi = a + e;
      return;
    }
    case Shape::Capsule:
      lo = {std::min(a.x, b.x) - radius, std::min(a.y, b.y) - radius, std::min(a.z, b.z) - radius};
      hi = {std::max(a.x, b.x) + radius, std::max(a.y, b.y) + radius, std::max(a.z, b.z) + radius};
      return;
  }
}

namespace {

bool same(const Vec3& a, const Vec3& b) {
  return a.x == b.x && a.y == b.y && a.z == b.z;
}

bool same(const Material& a, const Material& b) {
  return a.texture == b.texture && a.mapping == b.mapping && a.texelsPerMetre == b.texelsPerMetre &&
         a.gain == b.gain;
}

}  // namespace

bool sameSurface(const Primitive& a, const Primitive& b) {
  if (a.shape != b.shape || !same(a.a, b.a) || !same(a.b, b.b) || !same(a.radii, b.radii) ||
      a.radius != b.radius)
    return false;
  for (int i = 0; i < 3; ++i)
    if (!same(a.orient.r[i], b.orient.r[i])) return false;
  for (int i = 0; i < 6; ++i)
    if (!same(a.materials[i], b.materials[i])) return false;
  return true;
}

void prepare(Primitive& p, Vec3 origin) {
  if (p.shape == Primitive::Shape::Ellipsoid) {
    const Vec3 ol = p.orient.applyInverse(origin - p.a);
    p.preVec = {ol.x / p.radii.x, ol.y / p.radii.y, ol.z / p.radii.z};
    p.pre0 = dot(p.preVec, p.preVec) - 1;
    p.pre1 = 1 / p.radii.x;
    p.pre2 = 1 / p.radii.y;
  } else if (p.shape == Primitive::Shape::Capsule) {
    const Vec3 ba = p.b - p.a;
    p.preVec = origin - p.a;
    p.pre0 = dot(ba, p.preVec);
    p.pre1 = dot(p.preVec, p.preVec);
    p.pre2 = dot(ba, ba);
    p.axis = (1.0 / std::sqrt(p.pre2)) * ba;
    const Vec3 helper = std::abs(p.axis.y) < 0.9 ? Vec3{0, 1, 0} : Vec3{1, 0, 0};
    p.across1 = normalized(cross(p.axis, helper));
    p.across2 = cross(p.axis, p.across1);
    p.invRadius = 1.0 / p.radius;
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
  using namespace detail;
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

}  // namespace horopter::synth
