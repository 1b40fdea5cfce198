// A recorded track: one BodySample per line of a CSV file, what
// `horopter classify --track FILE` reads (and --write-track writes).
//
//   # horopter-body-track 1
//   frame,time_s,godfather,<part>_tracked,<part>_observed,<part>_u,<part>_v,
//     <part>_x,<part>_y,<part>_z   for part = head, left_hand, right_hand
//
// u, v: left rectified image, pixels; x, y, z: rig frame, metres ("nan" when
// the depth is unknown); flags 0 or 1. An optional last column `truth` holds
// the movement being performed (movementClassName), when it is known.
#pragma once

#include "horopter/core/export.hpp"

#include <string>
#include <vector>

#include "horopter/interaction/body.hpp"
#include "horopter/movement/movement.hpp"

namespace horopter {

// `truth`: empty, or one movement per sample (written as the truth column).
HOROPTER_API void writeBodyTrack(const std::string& path, const std::vector<BodySample>& samples,
                                 const std::vector<MovementClass>& truth = {});
// Throws horopter::Error naming the file and line for a malformed file.
// `truth` (if given) receives the truth column, empty when the file has none.
HOROPTER_API std::vector<BodySample> readBodyTrack(const std::string& path,
                                                   std::vector<MovementClass>* truth = nullptr);

}  // namespace horopter
