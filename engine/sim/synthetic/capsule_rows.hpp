// Which pixels of one image row can see a capsule: the rasteriser casts rays
// only there instead of over the capsule's whole screen rectangle.
//
// A ray that meets a capsule meets the infinite cylinder around its axis
// (the end spheres lie inside it). Along row y the ray direction is linear
// in the pixel's x, so intersectCapsule's discriminant h = b^2 - a c is a
// quadratic in x, and the pixels it can hit lie between the quadratic's roots.
// The span is widened by two pixels on each side: there |h| >= 4 |h2|, far
// above the rounding of the per-pixel test, so every pixel the test would
// draw stays inside and the image is the same as testing the whole rectangle.
// Where that cannot be guaranteed (the camera on or inside the cylinder, the
// quadratic nearly flat or opening upwards) the whole row is kept.
#pragma once

#include <algorithm>
#include <cmath>

#include "synthetic/primitives.hpp"
#include "synthetic/vec3.hpp"

namespace horopter::synth::detail {

class CapsuleRows {
 public:
  // `p` prepared for `centre`; the camera maps pixel (x, y) to the direction
  // rigToWorld (x - cx) / f, (y - cy) / f, 1.
  CapsuleRows(const Primitive& p, const Mat3& rigToWorld, double f, double cx, double cy, int width)
      : width_(width) {
    ba_ = p.b - p.a;
    oa_ = p.preVec;
    baba_ = p.pre2;
    baoa_ = p.pre0;
    c_ = baba_ * p.pre1 - baoa_ * baoa_ - p.radius * p.radius * baba_;
    // The camera must be clearly outside the infinite cylinder.
    outside_ = c_ > 1e-9 * baba_ * p.pre1;
    const Vec3 col0{rigToWorld.r[0].x, rigToWorld.r[1].x, rigToWorld.r[2].x};
    col1_ = {rigToWorld.r[0].y, rigToWorld.r[1].y, rigToWorld.r[2].y};
    const Vec3 col2{rigToWorld.r[0].z, rigToWorld.r[1].z, rigToWorld.r[2].z};
    q_ = (1.0 / f) * col0;
    p0_ = col2 - (cx / f) * col0;
    invF_ = 1.0 / f;
    cy_ = cy;
  }

  // Narrows [x0, x1) to the pixels of row y that may see the capsule; false
  // when none can.
  bool span(int y, int& x0, int& x1) const {
    if (!outside_) return x1 > x0;
    const Vec3 p = p0_ + ((y - cy_) * invF_) * col1_;  // the direction at x = 0
    const double b0 = dot(ba_, p), b1 = dot(ba_, q_);
    const double r0 = dot(oa_, p), r1 = dot(oa_, q_);
    const double d0 = dot(p, p), d1 = 2 * dot(p, q_), d2 = dot(q_, q_);
    const double bb0 = baba_ * r0 - baoa_ * b0, bb1 = baba_ * r1 - baoa_ * b1;
    const double h2 = bb1 * bb1 - c_ * (baba_ * d2 - b1 * b1);
    const double h1 = 2 * bb0 * bb1 - c_ * (baba_ * d1 - 2 * b0 * b1);
    const double h0 = bb0 * bb0 - c_ * (baba_ * d0 - b0 * b0);
    // The size of the terms the per-pixel test adds up, over the row.
    const double w = width_;
    const double bMax = std::abs(bb0) + std::abs(bb1) * w;
    const double baMax = std::abs(b0) + std::abs(b1) * w;
    const double scale =
        bMax * bMax + std::abs(c_) * (baba_ * (d0 + std::abs(d1) * w + d2 * w * w) + baMax * baMax);
    const double tolerance = 1e-9 * scale;
    if (!(h2 < 0) || -4 * h2 <= tolerance) return x1 > x0;  // keep the whole row
    const double disc = h1 * h1 - 4 * h2 * h0;
    if (!std::isfinite(disc)) return x1 > x0;  // keep the whole row
    double lo = 0, hi = 0;
    if (disc < 0) {
      // The parabola's top is below zero: no pixel, unless it only just is.
      if (disc / (4 * h2) > tolerance) return false;
      lo = hi = -h1 / (2 * h2);
    } else {
      const double s = std::sqrt(disc);
      lo = (-h1 + s) / (2 * h2);
      hi = (-h1 - s) / (2 * h2);
      if (lo > hi) std::swap(lo, hi);
    }
    if (!(hi > x0 - 3.0) || !(lo < x1 + 3.0)) return false;
    lo = std::max(lo, x0 - 3.0);  // both now within the int range
    hi = std::min(hi, x1 + 3.0);
    x0 = std::max(x0, static_cast<int>(std::floor(lo)) - 2);
    x1 = std::min(x1, static_cast<int>(std::ceil(hi)) + 3);
    return x1 > x0;
  }

 private:
  int width_;
  Vec3 ba_, oa_, col1_, q_, p0_;
  double baba_ = 0, baoa_ = 0, c_ = 0, invF_ = 0, cy_ = 0;
  bool outside_ = false;
};

}  // namespace horopter::synth::detail
