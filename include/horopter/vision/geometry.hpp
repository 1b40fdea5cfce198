// Horopter geometry on a rectified pair: the fixation point of a verging head,
// the Vieth-Mueller circle through the two camera centres and the fixation
// point, and that circle as a per-column disparity threshold table for
// horopterMask.
//
// Two frames, both rectified (x to the right, y down, z forward along the
// rectified optical axes), any length unit used consistently:
//  - the left camera frame (RectifiedGeometry / FixationPoint below): left
//    camera centre at the origin, right camera centre at (baseline, 0, 0);
//  - the cyclopean frame (Eigen vectors below): origin midway between the
//    camera centres, left camera at (-B/2, 0, 0), right at (+B/2, 0, 0).
// The circle lies in the horizontal plane y = 0 through both camera centres;
// the zone of interaction is the vertical cylinder over its inside, so only
// (x, z) of a point matters for inside / outside.
#pragma once

#include "horopter/core/export.hpp"

#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace horopter {

struct HOROPTER_API RectifiedGeometry {
  double focalPx = 0;   // focal length of the rectified pair, pixels
  double cx = 0;        // principal point column, pixels
  double baseline = 0;  // distance between the camera centres (> 0)
  double cy = 0;        // principal point row, pixels (only pointFromPixel uses it)
};

struct HOROPTER_API FixationPoint {
  double x = 0;  // lateral position in the left camera frame
  double z = 0;  // depth (> 0)
};

// The fixation point seen at column `u` of the left image with disparity
// `disparityPx` (> 0) pixels.
HOROPTER_API FixationPoint fixationFromDisparity(const RectifiedGeometry& geometry, double u,
                                                 double disparityPx);

// ---------------------------------------------------------------------------
// The cyclopean frame: fixation, circle, depth, 3-D points.

// A half-line: origin and direction (need not be unit length).
struct HOROPTER_API Ray {
  Eigen::Vector3d origin;
  Eigen::Vector3d direction;
};

// The Vieth-Mueller circle in the plane y = 0 of the cyclopean frame. It
// passes through both camera centres, so its centre is on the head's axis:
// (0, centreZ), radius^2 = (B/2)^2 + centreZ^2.
struct HOROPTER_API ViethMuellerCircle {
  double centreZ = 0;  // z of the centre (x = 0); negative when the circle is small
  double radius = 0;
  Eigen::Vector2d fixation{0, 0};  // (x, z) of the fixation point the circle was built from
};

// Each fixation helper returns the point in the cyclopean frame and throws
// horopter::Error for a degenerate head (zero or non-finite baseline) or a
// fixation that is not a finite point in front of the cameras (z > 0).

// (a) A symmetric vergence: each camera turned inward by vergenceRad / 2;
// the fixation is on the head's axis at z = (B/2) / tan(vergence / 2).
// 0 < vergenceRad < pi.
HOROPTER_API Eigen::Vector3d fixationFromVergence(double baseline, double vergenceRad);

// (b) Separate pan angles, measured from the rectified forward axis (+z),
// positive towards +x (turning right). The axes cross in front of the head
// only when leftPanRad > rightPanRad; the vergence angle is their difference.
HOROPTER_API Eigen::Vector3d fixationFromPanAngles(double baseline, double leftPanRad,
                                                   double rightPanRad);

// (c) The closest approach of two optical axes (3-D lines that need not
// meet): the midpoint of their common perpendicular. Throws for parallel axes
// (fixation at infinity) or a closest approach behind either camera.
HOROPTER_API Eigen::Vector3d fixationFromAxes(const Ray& left, const Ray& right);

// (d) A requested interaction distance: the fixation straight ahead at
// z = distance, so the zone reaches exactly that far on the head's axis.
HOROPTER_API Eigen::Vector3d fixationAtDistance(double baseline, double distance);

// The circle through (-B/2, 0), (B/2, 0) and the fixation's (x, z).
HOROPTER_API ViethMuellerCircle viethMuellerCircle(double baseline,
                                                   const Eigen::Vector3d& fixation);

// Inside the zone (the cylinder over the circle): strictly inside the circle
// in (x, z) and in front of the baseline (z > 0).
HOROPTER_API bool insideZone(const ViethMuellerCircle& circle, const Eigen::Vector3d& point);

// The vergence angle a point subtends between the two camera centres, rad.
HOROPTER_API double vergenceAngleAt(double baseline, const Eigen::Vector3d& point);

// Depth (z) of a disparity of disparityPx > 0 pixels: f B / d.
HOROPTER_API double depthFromDisparity(const RectifiedGeometry& geometry, double disparityPx);

// The 3-D point (cyclopean frame) of left pixel (u, v) with disparity
// disparityPx > 0: z = f B / d, x = (u - cx) z / f - B/2, y = (v - cy) z / f.
HOROPTER_API Eigen::Vector3d pointFromPixel(const RectifiedGeometry& geometry, double u, double v,
                                            double disparityPx);

// The fixation in the left camera frame, for horopterThresholds below.
HOROPTER_API FixationPoint toLeftCameraFrame(const RectifiedGeometry& geometry,
                                             const Eigen::Vector3d& point);

// ---------------------------------------------------------------------------
// The threshold table for horopterMask.
//
// One threshold per column, in 1/16 px. The mask kernel keeps a pixel of
// column u when its disparity D (1/16 px) satisfies D >= thresholds[u]
// (kernels/horopter_mask/horopter_mask_scalar.cpp); put the other way, the
// disparity must exceed thresholds[u] - 1. The viewing ray of left column u,
// t = (u - cx) / f, meets the circle once more besides the left camera
// centre, at depth
//   Z(u) = (B t + 2 zc) / (t^2 + 1)
// (zc: the centre's z, the same in both frames), where the circle's disparity
// is d(u) = f B / Z(u) px. Rounding: thresholds[u] = ceil(16 d(u)), clamped to
// INT16_MAX, so for integer D the test D >= ceil(16 d) is exactly D / 16 >= d:
// a point is kept iff its measured disparity is at least the circle's (the
// circle itself counts as inside); the only error is the 1/16 px quantisation
// of D itself. A column whose ray leaves the circle behind the camera
// (Z(u) <= 0) gets INT16_MAX: nothing in it is inside.
// Throws horopter::Error for a non-positive width, focal length, baseline or
// fixation depth.
HOROPTER_API std::vector<std::int16_t> horopterThresholds(const RectifiedGeometry& geometry,
                                                          int width, const FixationPoint& fixation);

// The same table for a circle from the helpers above, written into `out`
// (one entry per column, no allocation): cheap enough to recompute every frame
// from the head's current angles (one division per column).
HOROPTER_API void horopterThresholds(const RectifiedGeometry& geometry,
                                     const ViethMuellerCircle& circle, std::span<std::int16_t> out);

// ---------------------------------------------------------------------------
// Figures of the zone of interaction, in the baseline's unit.
struct HOROPTER_API ZoneExtent {
  double radius = 0;
  double centreZ = 0;
  double farOnAxis = 0;    // the zone spans z in (0, farOnAxis] on the head's axis (x = 0)
  double farOnCamera = 0;  // ... and z in (0, farOnCamera] on each camera's optical axis
  double widestZ = 0;      // depth of the widest chord (max(centreZ, 0))
  double widest = 0;       // its width
};
HOROPTER_API ZoneExtent zoneExtent(double baseline, const ViethMuellerCircle& circle);

// Width of the zone (chord of the circle parallel to the baseline) at depth
// z; 0 where the plane z misses the circle.
HOROPTER_API double zoneWidthAt(const ViethMuellerCircle& circle, double z);

}  // namespace horopter
