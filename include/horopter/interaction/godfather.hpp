// The godfather election: the one person the robot attends to. A subject
// becomes the godfather after staying inside the zone of interaction for
// `electS` seconds, and is released after `releaseS` seconds without being
// seen inside it. One at a time; subjects outside the zone never start a
// candidacy, whatever they do. Time comes from the caller (the frame's time),
// so the election is deterministic and testable with a fake clock.
#pragma once

#include "horopter/core/export.hpp"

#include <span>

#include "horopter/core/option_table.hpp"

#include <optional>

namespace horopter {

struct HOROPTER_API ElectionOptions {
  double electS = 2.0;    // T: continuous presence inside the zone to be elected
  double releaseS = 1.0;  // T_lost: absence from the zone that releases the godfather
  // A candidate survives detector misses shorter than this (a face missed for
  // a few frames is still inside the zone).
  double candidateGraceS = 0.3;
};

// The election options a user tunes (flags, help, ranges, JSON keys); validation
// checks them against it.
HOROPTER_API std::span<const NumberOption<ElectionOptions>> electionOptions();

enum class ElectionState { None, Candidate, Godfather };
HOROPTER_API const char* electionStateName(ElectionState state);

class HOROPTER_API GodfatherElection {
 public:
  explicit GodfatherElection(ElectionOptions options = {});  // throws for negative times

  // One observation of the current subject (the candidate or godfather, or a
  // new subject when there is none): std::nullopt when not seen this frame,
  // true when seen inside the zone, false when seen outside. Times must not
  // decrease. Returns the new state.
  ElectionState update(double timeS, std::optional<bool> seenInside);
  // Forget everything (the subject's track was lost for good).
  void reset();

  ElectionState state() const { return state_; }
  // Seconds the candidate has been inside (0 without one).
  double candidateS(double timeS) const;
  const ElectionOptions& options() const { return options_; }

 private:
  ElectionOptions options_;
  ElectionState state_ = ElectionState::None;
  double since_ = 0, lastInside_ = 0;
};

}  // namespace horopter
