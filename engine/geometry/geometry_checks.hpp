// Input checks shared by the geometry files: each throws horopter::Error with
// a message that says what to fix.
#pragma once

#include <Eigen/Core>
#include <string>

#include "horopter/vision/geometry.hpp"

namespace horopter::geometry_detail {

void checkBaseline(double baseline);
void checkRectified(const RectifiedGeometry& geometry);
// A fixation must be a finite point in front of the baseline (z > 0).
void checkFixation(const Eigen::Vector3d& fixation, const std::string& from);

}  // namespace horopter::geometry_detail
