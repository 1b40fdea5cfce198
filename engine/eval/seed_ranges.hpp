// The evaluation protocol's seed ranges (docs/evaluation.md), in one place.
// Every synthetic trial, training sequence and tuning sequence is drawn from
// a seed; the ranges are disjoint so that a reported figure never comes
// from trials that were looked at:
//   trial tuning      0 ..   499 999  diagnose, tune, look at stills freely
//   trial evaluation  500 000 ..   999 999  figures only, each block run once
//   model training    1 000 000 .. 1 999 999  the movement classifier's data
//   model tuning      2 000 000 .. 2 999 999  the classifier's parameters
// The commands enforce it: a trial range must lie in one trial range, and
// anything that looks inside trials (--diagnose, --verbose's per-part lines,
// --stills, --write-tracks) refuses evaluation seeds.
#pragma once

#include <cstdint>
#include <string>

namespace horopter::eval {

enum class SeedUse { TrialTuning, TrialEvaluation, ModelTraining, ModelTuning, Unassigned };

struct SeedRange {
  std::uint64_t first = 0, last = 0;  // inclusive
};

SeedRange seedRangeOf(SeedUse use);
SeedUse seedUseOf(std::uint64_t seed);
const char* seedUseName(SeedUse use);  // "tuning", "evaluation", ...

// The use of trial seeds first .. first + count - 1. Throws horopter::Error
// naming `option` unless they all lie in the trial tuning range or all in
// the trial evaluation range.
SeedUse trialSeedUse(std::uint64_t first, std::int64_t count, const std::string& option);

// Throws horopter::Error when `use` is evaluation: `what` (a flag that looks
// inside trials) is for tuning seeds only.
void requireTuningSeeds(SeedUse use, const std::string& what);

// The fewest trials a reportable figure comes from.
inline constexpr int kMinReportedTrials = 100;

}  // namespace horopter::eval
