// Small fixed-size vector and rotation types for the synthetic scene's ray
// caster (doubles: the disparity truth is computed from these depths).
#pragma once

#include <cmath>

namespace horopter::synth {

struct Vec3 {
  double x = 0, y = 0, z = 0;
};

inline Vec3 operator+(Vec3 a, Vec3 b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
inline Vec3 operator-(Vec3 a, Vec3 b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
inline Vec3 operator*(double s, Vec3 a) {
  return {s * a.x, s * a.y, s * a.z};
}
inline Vec3 operator*(Vec3 a, double s) {
  return {s * a.x, s * a.y, s * a.z};
}
inline double dot(Vec3 a, Vec3 b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline Vec3 cross(Vec3 a, Vec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double norm(Vec3 a) {
  return std::sqrt(dot(a, a));
}
inline Vec3 normalized(Vec3 a) {
  const double n = norm(a);
  return n > 0 ? (1.0 / n) * a : a;
}
inline Vec3 lerp(Vec3 a, Vec3 b, double s) {
  return a + s * (b - a);
}

// A rotation matrix, rows r[0..2]: apply() maps local to parent coordinates.
struct Mat3 {
  Vec3 r[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

  Vec3 apply(Vec3 v) const { return {dot(r[0], v), dot(r[1], v), dot(r[2], v)}; }
  // The inverse (transpose) applied: parent to local.
  Vec3 applyInverse(Vec3 v) const {
    return {r[0].x * v.x + r[1].x * v.y + r[2].x * v.z, r[0].y * v.x + r[1].y * v.y + r[2].y * v.z,
            r[0].z * v.x + r[1].z * v.y + r[2].z * v.z};
  }
};

// Rotation about the vertical (y, pointing down) axis by `yaw`: positive yaw
// turns +z towards +x (the view to the right).
inline Mat3 rotationY(double yaw) {
  const double c = std::cos(yaw), s = std::sin(yaw);
  Mat3 m;
  m.r[0] = {c, 0, s};
  m.r[1] = {0, 1, 0};
  m.r[2] = {-s, 0, c};
  return m;
}

// Rotation about x by `pitch`: positive pitch turns +z towards +y (looking down).
inline Mat3 rotationX(double pitch) {
  const double c = std::cos(pitch), s = std::sin(pitch);
  Mat3 m;
  m.r[0] = {1, 0, 0};
  m.r[1] = {0, c, s};
  m.r[2] = {0, -s, c};
  return m;
}

inline Mat3 operator*(const Mat3& a, const Mat3& b) {
  Mat3 m;
  for (int i = 0; i < 3; ++i) {
    const Vec3 col0{b.r[0].x, b.r[1].x, b.r[2].x};
    const Vec3 col1{b.r[0].y, b.r[1].y, b.r[2].y};
    const Vec3 col2{b.r[0].z, b.r[1].z, b.r[2].z};
    m.r[i] = {dot(a.r[i], col0), dot(a.r[i], col1), dot(a.r[i], col2)};
  }
  return m;
}

}  // namespace horopter::synth
