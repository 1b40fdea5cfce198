// The godfather election's state machine; see horopter/interaction/godfather.hpp.
#include "horopter/interaction/godfather.hpp"

#include <cmath>

#include "horopter/core/error.hpp"

namespace horopter {

const char* electionStateName(ElectionState state) {
  switch (state) {
    case ElectionState::None:
      return "none";
    case ElectionState::Candidate:
      return "candidate";
    case ElectionState::Godfather:
      return "godfather";
  }
  return "unknown";
}

std::span<const NumberOption<ElectionOptions>> electionOptions() {
  using O = ElectionOptions;
  static const NumberOption<O> table[] = {
      {"electS", "--elect-s", "s", 0, 3600, "seconds inside the zone to become the godfather",
       &O::electS},
      {"releaseS", "--release-s", "s", 0, 3600, "seconds outside the zone to be released",
       &O::releaseS},
  };
  return table;
}

GodfatherElection::GodfatherElection(ElectionOptions options) : options_(options) {
  // electS and releaseS: their table's ranges; candidateGraceS is internal.
  checkRanges(electionOptions(), options);
  if (!(options.candidateGraceS >= 0) || !std::isfinite(options.candidateGraceS))
    throw Error("godfather election's candidate grace must be finite and >= 0 seconds");
}

void GodfatherElection::reset() {
  state_ = ElectionState::None;
  since_ = lastInside_ = 0;
}

double GodfatherElection::candidateS(double timeS) const {
  return state_ == ElectionState::None ? 0 : timeS - since_;
}

ElectionState GodfatherElection::update(double timeS, std::optional<bool> seenInside) {
  const bool inside = seenInside.value_or(false);
  switch (state_) {
    case ElectionState::None:
      if (inside) {
        state_ = ElectionState::Candidate;
        since_ = lastInside_ = timeS;
      }
      break;
    case ElectionState::Candidate:
      if (inside) {
        lastInside_ = timeS;
      } else if (timeS - lastInside_ > options_.candidateGraceS) {
        reset();
        break;
      }
      if (timeS - since_ >= options_.electS) state_ = ElectionState::Godfather;
      break;
    case ElectionState::Godfather:
      if (inside)
        lastInside_ = timeS;
      else if (timeS - lastInside_ >= options_.releaseS)
        reset();
      break;
  }
  // An election with T = 0 elects on the first sighting.
  if (state_ == ElectionState::Candidate && timeS - since_ >= options_.electS)
    state_ = ElectionState::Godfather;
  return state_;
}

}  // namespace horopter
