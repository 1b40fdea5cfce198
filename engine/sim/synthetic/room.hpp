// The static room: walls, floor, ceiling, furniture and posters, in world
// coordinates (x right, y down, z forward; the rig's cyclopean point at the
// origin).
#pragma once

#include <vector>

#include "synthetic/primitives.hpp"

namespace horopter::synth::room {

// The room's inner walls.
inline constexpr double kLeftX = -2.6, kRightX = 2.6;
inline constexpr double kCeilingY = -1.5, kFloorY = 1.45;  // the rig is 1.45 m above the floor
inline constexpr double kBehindZ = -1.0, kBackZ = 5.0;

// `furnished`: furniture boxes (skin-coloured wood among them) and posters;
// without: only the six inner walls (for plane tests). `skinClutter` adds
// skin-coloured panels behind the person, a rug and a skin-toned poster.
std::vector<Primitive> build(bool furnished, bool skinClutter = false);

}  // namespace horopter::synth::room
