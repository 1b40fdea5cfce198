// Ground truth from the rendered depth: disparity, the zone of interaction,
// occlusion, and the people's head and hands in 2-D and 3-D.
#pragma once

#include <opencv2/core.hpp>

#include "horopter/sim/synthetic_scene.hpp"
#include "synthetic/people.hpp"
#include "synthetic/rasteriser.hpp"
#include "synthetic/row_intervals.hpp"

namespace horopter::synth {

// The Vieth-Mueller circle in the rig's plane y = 0, through (-B/2, 0),
// (B/2, 0) and the fixation point (0, D).
class ZoneCircle {
 public:
  ZoneCircle(double baselineM, double vergence);
  double fixationDistance() const { return fixation_; }  // +inf for vergence 0
  double centreZ() const { return centreZ_; }
  double radius() const { return radius_; }
  // Strictly inside, for a rig-frame (x, z). Written as
  // x^2 + z^2 - 2 z zc < B^2/4 (r^2 - zc^2 = B^2/4), which stays exact for a
  // far fixation; vergence 0 (fixation at infinity) leaves z > 0.
  bool inside(double x, double z) const;

 private:
  double halfBaseline_, fixation_, centreZ_, radius_;
};

// disparity, inside and occluded of `truth` inside `rect` (rows split as in
// render(), into at most `stripes` parts) (the maps must
// already have the image's size and types), from the two views' depths.
void pixelTruth(const Camera& left, const Layer& leftLayer, const Layer& rightLayer,
                double baselineM, const ZoneCircle& zone, cv::Rect rect, FrameTruth& truth,
                double stripes = -1);
// The same inside `rows` (intervals per row of the image).
void pixelTruth(const Camera& left, const Layer& leftLayer, const Layer& rightLayer,
                double baselineM, const ZoneCircle& zone, const RowIntervals& rows,
                FrameTruth& truth, double stripes = -1);
// Allocates the three maps of `truth` for a width x height image.
void allocatePixelTruth(int width, int height, FrameTruth& truth);

// One person's truth in the left view (`leftLayer` decides visibility).
PersonTruth personTruth(const Camera& left, const Layer& leftLayer, double baselineM,
                        const ZoneCircle& zone, int id, const PersonPose& pose);

}  // namespace horopter::synth
