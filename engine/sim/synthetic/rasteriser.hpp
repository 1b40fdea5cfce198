// Renders primitives into a colour + depth layer by casting one ray per pixel
// inside each primitive's screen rectangle, narrowed for a capsule to the
// span of each row it can hit (a z-buffer of exact ray depths).
#pragma once

#include <opencv2/core.hpp>

#include <vector>

#include "synthetic/primitives.hpp"
#include "synthetic/row_intervals.hpp"
#include "synthetic/vec3.hpp"

namespace horopter::synth {

// One rectified pinhole view: pixel (x, y) looks along
// rig (x - cx) / f, (y - cy) / f, 1, turned into the world by `rigToWorld`.
struct Camera {
  Vec3 centre;      // world
  Mat3 rigToWorld;  // the head's orientation
  double f = 0, cx = 0, cy = 0;
  int width = 0, height = 0;

  // The ray through pixel (x, y); its t is the rig depth.
  Ray ray(double x, double y) const;
  // The rig-frame coordinates of a world point, relative to this camera.
  Vec3 toCamera(Vec3 world) const { return rigToWorld.applyInverse(world - centre); }
  // The pixel rectangle that contains the projection of a world box; the
  // whole image when part of the box is behind (or at) the camera.
  cv::Rect screenRect(Vec3 lo, Vec3 hi) const;
};

struct Layer {
  cv::Mat colour;  // CV_8UC3
  cv::Mat depth;   // CV_64FC1, rig depth Z of the visible surface (+inf: nothing yet)

  void reset(int width, int height);
};

// The rectangle of pixels a primitive may draw into (the whole image for the
// room), within the image.
cv::Rect screenRect(const Camera& camera, const Primitive& primitive);
// Adds to `out` the pixels render() casts rays through for `primitive`
// (per row, a capsule's span within its rectangle): it draws nowhere else.
void coverage(const Camera& camera, const Primitive& primitive, RowIntervals& out);

// Draws `primitives` over `layer` where they are nearer than what it holds,
// inside `only` (nullptr: the whole image); returns the union of the pixel
// rectangles it looked at. Rows are split across OpenCV's threads, into at
// most `stripes` parts (-1: OpenCV's choice; 1: the calling thread); the
// result does not depend on the split.
cv::Rect render(const Camera& camera, const std::vector<Primitive>& primitives, Layer& layer,
                const RowIntervals* only = nullptr, double stripes = -1);

}  // namespace horopter::synth
