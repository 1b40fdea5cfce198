// A frame the simulator made: the application's Frame with the scene's
// ground truth. The simulator's sources make these (newFrame); evaluation
// and annotation code asks truthOf() for the truth.
#pragma once

#include "horopter/app/frame.hpp"
#include "horopter/sim/synthetic_scene.hpp"

namespace horopter::sim {

struct SimFrame : Frame {
  synth::FrameTruth truth;
};

// The frame's ground truth when the simulator made it; nullptr otherwise.
inline const synth::FrameTruth* truthOf(const ScheduledFrame& frame) {
  const auto* sim = dynamic_cast<const SimFrame*>(&frame);
  return sim != nullptr ? &sim->truth : nullptr;
}

}  // namespace horopter::sim
