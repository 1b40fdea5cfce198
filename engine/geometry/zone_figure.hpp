// A top-down picture of the zone of interaction: the cameras, their fields of
// view, the Vieth-Mueller circle with its inside shaded, the fixation point
// and the visual axes, with a scale bar. Used by `horopter geometry`.
#pragma once

#include <opencv2/core.hpp>

#include "horopter/vision/geometry.hpp"

namespace horopter {

// `width`: the rectified image width in pixels (for the fields of view).
cv::Mat drawZoneTopDown(const RectifiedGeometry& geometry, int width,
                        const ViethMuellerCircle& circle, int canvasPx = 900);

}  // namespace horopter
