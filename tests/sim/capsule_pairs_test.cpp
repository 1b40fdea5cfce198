// The renderer's two-pixels-at-a-time capsule test against the scalar one:
// the same pixels hit, with bit-identical depths, normals and texture
// coordinates, for capsules seen along, across and end-on, near and far.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

#include "synthetic/capsule_pairs.hpp"
#include "synthetic/intersections.hpp"

namespace horopter::synth::detail {
namespace {

bool sameBits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

TEST(SyntheticCapsulePairs, SameHitsAsTheScalarTest) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  Camera camera;
  camera.width = 160;
  camera.height = 120;
  camera.f = 140;
  camera.cx = 79.5;
  camera.cy = 59.5;
  std::vector<double> columnX(static_cast<std::size_t>(camera.width));
  for (int x = 0; x < camera.width; ++x)
    columnX[static_cast<std::size_t>(x)] = (x - camera.cx) / camera.f;
  int hitsSeen = 0, capsSeen = 0;
  for (int trial = 0; trial < 60; ++trial) {
    camera.rigToWorld = rotationY(0.3 * u(rng)) * rotationX(0.2 * u(rng));
    camera.centre = {0.05 * u(rng), 0.05 * u(rng), 0};
    // Some capsules point at the camera (end-on), some lie across the view.
    const Vec3 a{0.4 * u(rng), 0.3 * u(rng), 1.2 + 0.5 * u(rng)};
    const Vec3 dir = trial % 4 == 0 ? Vec3{0.02 * u(rng), 0.02 * u(rng), -1}
                                    : Vec3{u(rng), u(rng), 0.5 * u(rng)};
    Primitive p = makeCapsule(a, a + (0.1 + 0.3 * (u(rng) + 1)) * normalized(dir),
                              0.03 + 0.05 * (u(rng) + 1), Material{});
    prepare(p, camera.centre);
    for (int y = 0; y < camera.height; y += 3) {
      const double rowY = (y - camera.cy) / camera.f;
      // Something already drawn in part of the row: a depth limit.
      std::vector<double> depth(static_cast<std::size_t>(camera.width), 1e30);
      for (int x = 40; x < 80; ++x)
        depth[static_cast<std::size_t>(x)] = 1.1;
      Hit hits[160];
      int xs[160];
      const int n =
          capsuleRowHits(p, camera, columnX.data(), rowY, 0, camera.width, depth.data(), hits, xs);
      int k = 0;
      for (int x = 0; x < camera.width; ++x) {
        Ray ray;
        ray.o = camera.centre;
        ray.d = camera.rigToWorld.apply(Vec3{columnX[static_cast<std::size_t>(x)], rowY, 1.0});
        Hit hit;
        if (!intersectCapsule(p, ray, depth[static_cast<std::size_t>(x)], hit)) continue;
        ++hitsSeen;
        const Vec3 rel = ray.o + hit.t * ray.d - p.a;
        if (dot(rel, p.axis) <= 0 || dot(rel, p.axis) >= std::sqrt(p.pre2)) ++capsSeen;
        ASSERT_LT(k, n) << "trial " << trial << " row " << y << " x " << x;
        ASSERT_EQ(xs[k], x) << "trial " << trial << " row " << y;
        EXPECT_TRUE(sameBits(hits[k].t, hit.t)) << x;
        EXPECT_TRUE(sameBits(hits[k].normal.x, hit.normal.x)) << x;
        EXPECT_TRUE(sameBits(hits[k].normal.y, hit.normal.y)) << x;
        EXPECT_TRUE(sameBits(hits[k].normal.z, hit.normal.z)) << x;
        EXPECT_TRUE(sameBits(hits[k].u, hit.u)) << x;
        EXPECT_TRUE(sameBits(hits[k].v, hit.v)) << x;
        EXPECT_EQ(hits[k].face, hit.face);
        ++k;
      }
      EXPECT_EQ(k, n) << "trial " << trial << " row " << y << ": extra hits";
    }
  }
  EXPECT_GT(hitsSeen, 1000) << "the capsules were mostly out of view";
  EXPECT_GT(capsSeen, 50) << "the end caps were hardly tested";
}

}  // namespace
}  // namespace horopter::synth::detail
