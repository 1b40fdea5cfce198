// Scoring movement decisions against the truth, per movement performed (the
// paper's Table III):
//   - a segment is a maximal run of frames with the same movement label;
//   - its decision is the first one from its first frame to its last frame
//     plus `graceFrames` (never past the next segment's start);
//   - the tracker is lost in a segment when it was on the performer in fewer
//     than half of the segment's frames;
//   tracker loss          = lost segments / segments
//   classification rate   = correct decisions / segments with the tracker on
//   real classification   = correct decisions with the tracker on / segments
//                           (a lost tracker counts as a miss)
// Segments cut by the end of the sequence, and segments where the performer
// is not (yet) the godfather by the truth for most frames, are not scored. Decisions outside
// every segment's window are counted as spurious.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "horopter/movement/movement.hpp"

namespace horopter {

struct ScoredFrame {
  MovementClass truth = MovementClass::None;
  std::optional<MovementClass> decision;
  bool onTarget = true;  // the tracker followed the performer this frame
  // The performer is the godfather by the truth (the interaction has begun);
  // segments mostly outside the interaction are not scored.
  bool interacting = true;
};

struct MovementSegment {
  MovementClass truth = MovementClass::None;
  std::int64_t firstFrame = 0, lastFrame = 0;
  bool trackerLost = false;
  std::optional<MovementClass> decided;
  bool correct() const { return decided && *decided == truth; }
};

std::vector<MovementSegment> scoreSegments(const std::vector<ScoredFrame>& frames, int graceFrames);

struct MovementScore {
  int segments = 0, lost = 0, correct = 0, correctTracked = 0, spurious = 0;
  double trackerLossPct() const { return segments ? 100.0 * lost / segments : 0; }
  double classificationPct() const {
    return segments > lost ? 100.0 * correctTracked / (segments - lost) : 0;
  }
  double realClassificationPct() const { return segments ? 100.0 * correctTracked / segments : 0; }
  void add(const MovementScore& other);
};

MovementScore summariseSegments(const std::vector<ScoredFrame>& frames, int graceFrames);

}  // namespace horopter
