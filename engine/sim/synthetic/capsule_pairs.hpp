// intersectCapsule for the pixels of one row, two at a time (SSE2, in the
// x86-64 baseline). Every lane performs the scalar test's operations in the
// same order (no fused multiply-adds: -ffp-contract=off), so the hits are
// bit-identical, the end caps (and rays along the axis) included: they are
// tested two at a time too, as the scalar test does them.
#pragma once

#include <limits>

#include "synthetic/intersections.hpp"
#include "synthetic/rasteriser.hpp"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace horopter::synth::detail {

// Tests pixels xb <= x < xe of the row whose rig direction y is `rowY`
// (direction x from `columnX`); for each pixel hit nearer than depth[x],
// appends its hit and x. Returns how many were appended.
inline int capsuleRowHits(const Primitive& p, const Camera& camera, const double* columnX,
                          double rowY, int xb, int xe, const double* depth, Hit* hits, int* xs) {
  int n = 0;
  auto scalar = [&](int x) {
    Ray ray;
    ray.o = camera.centre;
    ray.d = camera.rigToWorld.apply(Vec3{columnX[x], rowY, 1.0});
    if (intersectCapsule(p, ray, depth[x], hits[n])) xs[n++] = x;
  };
  int x = xb;
#if defined(__SSE2__)
  const Mat3& m = camera.rigToWorld;
  const Vec3 ba = p.b - p.a, oa = p.preVec;
  const double baba = p.pre2, baoa = p.pre0, oaoa = p.pre1, r = p.radius;
  const double c = baba * oaoa - baoa * baoa - r * r * baba;
  const double tiny = 1e-12 * baba;
  auto set = [](double v) { return _mm_set1_pd(v); };
  auto dot3 = [](__m128d ax, __m128d ay, __m128d az, __m128d bx, __m128d by, __m128d bz) {
    return _mm_add_pd(_mm_add_pd(_mm_mul_pd(ax, bx), _mm_mul_pd(ay, by)), _mm_mul_pd(az, bz));
  };
  auto select = [](__m128d mask, __m128d a, __m128d b) {
    return _mm_or_pd(_mm_and_pd(mask, a), _mm_andnot_pd(mask, b));
  };
  const __m128d sign = set(-0.0), zero = _mm_setzero_pd();
  const __m128d vy = set(rowY);
  // The row part of each direction component: r.x * vx + (r.y * vy), then + r.z.
  const __m128d r0x = set(m.r[0].x), r1x = set(m.r[1].x), r2x = set(m.r[2].x);
  const __m128d r0y = _mm_mul_pd(set(m.r[0].y), vy), r1y = _mm_mul_pd(set(m.r[1].y), vy),
                r2y = _mm_mul_pd(set(m.r[2].y), vy);
  const __m128d r0z = set(m.r[0].z), r1z = set(m.r[1].z), r2z = set(m.r[2].z);
  // An end sphere of centre cc: oc = ray.o - cc and c = oc.oc - r^2 are the
  // same for every ray (computed as the scalar test does); the ray's tc is
  // (-b - sqrt(b^2 - dd c)) / dd with b = d.oc.
  struct Cap {
    __m128d ocx, ocy, ocz, c;
    __m128d tc(__m128d dx, __m128d dy, __m128d dz, __m128d dd) const {
      const __m128d b =
          _mm_add_pd(_mm_add_pd(_mm_mul_pd(dx, ocx), _mm_mul_pd(dy, ocy)), _mm_mul_pd(dz, ocz));
      const __m128d h = _mm_sub_pd(_mm_mul_pd(b, b), _mm_mul_pd(dd, c));
      return _mm_div_pd(_mm_sub_pd(_mm_xor_pd(b, _mm_set1_pd(-0.0)), _mm_sqrt_pd(h)), dd);
    }
  };
  auto cap = [&](const Vec3& cc) {
    const Vec3 oc = camera.centre - cc;
    return Cap{set(oc.x), set(oc.y), set(oc.z), set(dot(oc, oc) - r * r)};
  };
  const Cap capA = cap(p.a), capB = cap(p.b);
  for (; x + 1 < xe; x += 2) {
    const __m128d vx = _mm_loadu_pd(columnX + x);
    const __m128d dx = _mm_add_pd(_mm_add_pd(_mm_mul_pd(r0x, vx), r0y), r0z);
    const __m128d dy = _mm_add_pd(_mm_add_pd(_mm_mul_pd(r1x, vx), r1y), r1z);
    const __m128d dz = _mm_add_pd(_mm_add_pd(_mm_mul_pd(r2x, vx), r2y), r2z);
    const __m128d bard = dot3(set(ba.x), set(ba.y), set(ba.z), dx, dy, dz);
    const __m128d rdoa = dot3(dx, dy, dz, set(oa.x), set(oa.y), set(oa.z));
    const __m128d dd = dot3(dx, dy, dz, dx, dy, dz);
    const __m128d a = _mm_sub_pd(_mm_mul_pd(set(baba), dd), _mm_mul_pd(bard, bard));
    const __m128d cylinder = _mm_cmpgt_pd(a, _mm_mul_pd(set(tiny), dd));
    const __m128d b = _mm_sub_pd(_mm_mul_pd(set(baba), rdoa), _mm_mul_pd(set(baoa), bard));
    const __m128d h = _mm_sub_pd(_mm_mul_pd(b, b), _mm_mul_pd(a, set(c)));
    const __m128d misses = _mm_and_pd(cylinder, _mm_cmplt_pd(h, zero));
    const __m128d tb = _mm_div_pd(_mm_sub_pd(_mm_xor_pd(b, sign), _mm_sqrt_pd(h)), a);
    const __m128d y = _mm_add_pd(set(baoa), _mm_mul_pd(tb, bard));
    const __m128d body = _mm_and_pd(_mm_andnot_pd(misses, cylinder),
                                    _mm_and_pd(_mm_cmpgt_pd(y, zero), _mm_cmplt_pd(y, set(baba))));
    // The lanes the scalar test sends to the end caps (or a ray along the
    // axis): neither a miss of the cylinder nor a hit on the body.
    const __m128d caps = _mm_andnot_pd(_mm_or_pd(misses, body), _mm_cmpeq_pd(zero, zero));
    const int bodyMask = _mm_movemask_pd(body), capsMask = _mm_movemask_pd(caps);
    if (bodyMask == 0 && capsMask == 0) continue;
    // The hit and its point on the axis: on the body, a + (y / baba) ba.
    const __m128d s = _mm_div_pd(y, set(baba));
    __m128d t = tb;
    __m128d px = _mm_add_pd(set(p.a.x), _mm_mul_pd(s, set(ba.x)));
    __m128d py = _mm_add_pd(set(p.a.y), _mm_mul_pd(s, set(ba.y)));
    __m128d pz = _mm_add_pd(set(p.a.z), _mm_mul_pd(s, set(ba.z)));
    __m128d found = body;
    if (capsMask != 0) {
      // The caps as the scalar test does them, end a then end b: a sphere's
      // hit tc counts when 0 < tc < the best so far (a lane that misses the
      // sphere, h < 0, gets tc = NaN, which never counts).
      const __m128d inf = set(std::numeric_limits<double>::infinity());
      const __m128d tcA = capA.tc(dx, dy, dz, dd), tcB = capB.tc(dx, dy, dz, dd);
      const __m128d takeA = _mm_and_pd(_mm_cmpgt_pd(tcA, zero), _mm_cmplt_pd(tcA, inf));
      const __m128d bestA = select(takeA, tcA, inf);
      const __m128d takeB = _mm_and_pd(_mm_cmpgt_pd(tcB, zero), _mm_cmplt_pd(tcB, bestA));
      const __m128d best = select(takeB, tcB, bestA);
      t = select(caps, best, t);
      px = select(caps, select(takeB, set(p.b.x), set(p.a.x)), px);
      py = select(caps, select(takeB, set(p.b.y), set(p.a.y)), py);
      pz = select(caps, select(takeB, set(p.b.z), set(p.a.z)), pz);
      found = _mm_or_pd(found, _mm_and_pd(caps, _mm_or_pd(takeA, takeB)));
    }
    const __m128d tMax = _mm_loadu_pd(depth + x);
    const __m128d inRange = _mm_and_pd(_mm_cmpnle_pd(t, set(kTMin)), _mm_cmpnge_pd(t, tMax));
    const int hitMask = _mm_movemask_pd(_mm_and_pd(found, inRange));
    if (hitMask == 0) continue;  // behind what is there, too near, or no cap
    alignas(16) double out[6][2];
    {
      const __m128d qx = _mm_add_pd(set(camera.centre.x), _mm_mul_pd(t, dx));
      const __m128d qy = _mm_add_pd(set(camera.centre.y), _mm_mul_pd(t, dy));
      const __m128d qz = _mm_add_pd(set(camera.centre.z), _mm_mul_pd(t, dz));
      const __m128d invR = set(p.invRadius);
      const __m128d nx = _mm_mul_pd(invR, _mm_sub_pd(qx, px));
      const __m128d ny = _mm_mul_pd(invR, _mm_sub_pd(qy, py));
      const __m128d nz = _mm_mul_pd(invR, _mm_sub_pd(qz, pz));
      // fastAtan2(n . across2, n . across1), lane by lane as the scalar one.
      const __m128d ay0 = dot3(nx, ny, nz, set(p.across2.x), set(p.across2.y), set(p.across2.z));
      const __m128d ax0 = dot3(nx, ny, nz, set(p.across1.x), set(p.across1.y), set(p.across1.z));
      const __m128d ax = _mm_andnot_pd(sign, ax0), ay = _mm_andnot_pd(sign, ay0);
      const __m128d mx = select(_mm_cmplt_pd(ax, ay), ay, ax);  // std::max(ax, ay)
      const __m128d mn = select(_mm_cmplt_pd(ay, ax), ay, ax);  // std::min(ax, ay)
      const __m128d ratio = _mm_div_pd(mn, mx);
      const __m128d sq = _mm_mul_pd(ratio, ratio);
      __m128d angle = _mm_mul_pd(set(-0.0464964749), sq);
      angle = _mm_mul_pd(_mm_add_pd(angle, set(0.15931422)), sq);
      angle = _mm_mul_pd(_mm_mul_pd(_mm_sub_pd(angle, set(0.327622764)), sq), ratio);
      angle = _mm_add_pd(angle, ratio);
      angle = select(_mm_cmpgt_pd(ay, ax), _mm_sub_pd(set(1.57079637), angle), angle);
      angle = select(_mm_cmplt_pd(ax0, zero), _mm_sub_pd(set(3.14159265), angle), angle);
      angle = select(_mm_cmplt_pd(ay0, zero), _mm_xor_pd(angle, sign), angle);
      angle = select(_mm_cmpeq_pd(mx, zero), zero, angle);
      const __m128d u = _mm_mul_pd(set(r), angle);
      const __m128d v =
          dot3(_mm_sub_pd(qx, set(p.a.x)), _mm_sub_pd(qy, set(p.a.y)), _mm_sub_pd(qz, set(p.a.z)),
               set(p.axis.x), set(p.axis.y), set(p.axis.z));
      _mm_store_pd(out[0], t);
      _mm_store_pd(out[1], nx);
      _mm_store_pd(out[2], ny);
      _mm_store_pd(out[3], nz);
      _mm_store_pd(out[4], u);
      _mm_store_pd(out[5], v);
    }
    for (int lane = 0; lane < 2; ++lane) {
      if (!(hitMask & (1 << lane))) continue;
      Hit& hit = hits[n];
      hit = Hit{};
      hit.t = out[0][lane];
      hit.normal = {out[1][lane], out[2][lane], out[3][lane]};
      hit.u = out[4][lane];
      hit.v = out[5][lane];
      xs[n++] = x + lane;
    }
  }
#endif
  for (; x < xe; ++x)
    scalar(x);
  return n;
}

}  // namespace horopter::synth::detail
