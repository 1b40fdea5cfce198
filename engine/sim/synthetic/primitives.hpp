// The shapes of the synthetic scene and their exact ray intersections: boxes
// (seen from outside, and the room seen from inside), yaw-oriented
// ellipsoids, capsules. Every hit returns the ray parameter t; rays are built
// so that t is the rig depth Z of the hit (see rasteriser.hpp), which makes
// the disparity truth f * B / t exact.
#pragma once

#include <opencv2/core.hpp>

#include "synthetic/textures.hpp"
#include "synthetic/vec3.hpp"

namespace horopter::synth {

// How a surface gets its colour: texture * gain * lighting.
struct Material {
  enum class Mapping {
    Tiled,    // the texture repeats, texelsPerMetre along the surface
    Stretch,  // one copy over the whole face (posters)
    Face,     // ellipsoid front: a photograph; back: `gain` as hair colour
  };
  TextureId texture = TextureId::Noise;
  Mapping mapping = Mapping::Tiled;
  double texelsPerMetre = 256;
  cv::Vec3f gain{1, 1, 1};  // multiplies the texture (BGR)
};

struct Primitive {
  enum class Shape { Box, Room, Ellipsoid, Capsule };
  Shape shape = Shape::Box;
  Vec3 a, b;   // Box/Room: min and max corners; Capsule: the axis ends; Ellipsoid: a = centre
  Vec3 radii;  // Ellipsoid: half-axes in its local frame (x right, y down, z front)
  double radius = 0;  // Capsule
  Mat3 orient;        // Ellipsoid: local to world
  // Box/Room: one per face, index 2 * axis + (max face ? 1 : 0); others use [0].
  Material materials[6];

  // Per-view constants of the ray tests, set by prepare() for one ray origin.
  Vec3 preVec;
  double pre0 = 0, pre1 = 0, pre2 = 0;
  // Capsule, also set by prepare() (they do not depend on the origin, but are
  // needed per hit): the unit axis, two unit vectors across it for the
  // texture's angle, and 1 / radius.
  Vec3 axis, across1, across2;
  double invRadius = 0;

  // The world-space bounding box (for the screen rectangle).
  void bounds(Vec3& lo, Vec3& hi) const;
};

// Whether two primitives are the same surface (shape, placement, materials;
// not the per-view constants): they draw the same pixels.
bool sameSurface(const Primitive& a, const Primitive& b);

// Computes what the ray tests of `p` share for every ray from `origin`;
// intersect() then needs rays starting there.
void prepare(Primitive& p, Vec3 origin);

Primitive makeBox(Vec3 lo, Vec3 hi, const Material& material);
Primitive makeEllipsoid(Vec3 centre, Vec3 radii, double yaw, const Material& material);
Primitive makeCapsule(Vec3 a, Vec3 b, double radius, const Material& material);

// A ray o + t d; d is not unit length: its rig z is 1, so t is the rig depth.
struct Ray {
  Vec3 o, d;
};

struct Hit {
  double t = 0;
  Vec3 normal;          // unit, world
  double u = 0, v = 0;  // surface coordinates: metres (Tiled) or [0, 1] (Stretch, Face)
  int face = 0;         // material index
  bool back = false;    // Face mapping: the back of the head
};

// The nearest hit with tMin < t < tMax, or false; `p` prepared for ray.o.
bool intersect(const Primitive& p, const Ray& ray, double tMax, Hit& hit);

// shade(): synthetic/shading.hpp.

}  // namespace horopter::synth
