// See seed_ranges.hpp.
#include "eval/seed_ranges.hpp"

#include "horopter/core/error.hpp"

namespace horopter::eval {

SeedRange seedRangeOf(SeedUse use) {
  switch (use) {
    case SeedUse::TrialTuning:
      return {0, 499'999};
    case SeedUse::TrialEvaluation:
      return {500'000, 999'999};
    case SeedUse::ModelTraining:
      return {1'000'000, 1'999'999};
    case SeedUse::ModelTuning:
      return {2'000'000, 2'999'999};
    case SeedUse::Unassigned:
      break;
  }
  return {3'000'000, UINT64_MAX};
}

SeedUse seedUseOf(std::uint64_t seed) {
  for (SeedUse use : {SeedUse::TrialTuning, SeedUse::TrialEvaluation, SeedUse::ModelTraining,
                      SeedUse::ModelTuning}) {
    const SeedRange r = seedRangeOf(use);
    if (seed >= r.first && seed <= r.last) return use;
  }
  return SeedUse::Unassigned;
}

const char* seedUseName(SeedUse use) {
  switch (use) {
    case SeedUse::TrialTuning:
      return "tuning";
    case SeedUse::TrialEvaluation:
      return "evaluation";
    case SeedUse::ModelTraining:
      return "model-training";
    case SeedUse::ModelTuning:
      return "model-tuning";
    case SeedUse::Unassigned:
      break;
  }
  return "unassigned";
}

namespace {
std::string rangeText(SeedUse use) {
  const SeedRange r = seedRangeOf(use);
  return std::to_string(r.first) + "-" + std::to_string(r.last);
}
}  // namespace

SeedUse trialSeedUse(std::uint64_t first, std::int64_t count, const std::string& option) {
  if (count < 1) throw Error(option + ": at least one trial is needed");
  const std::uint64_t last = first + static_cast<std::uint64_t>(count - 1);
  const SeedUse use = seedUseOf(first);
  if (last < first || seedUseOf(last) != use ||
      (use != SeedUse::TrialTuning && use != SeedUse::TrialEvaluation))
    throw Error(option + ": trial seeds " + std::to_string(first) + "-" + std::to_string(last) +
                " must lie within the tuning range (" + rangeText(SeedUse::TrialTuning) +
                ") or within the evaluation range (" + rangeText(SeedUse::TrialEvaluation) +
                "); seeds from " + std::to_string(seedRangeOf(SeedUse::ModelTraining).first) +
                " on trained and tuned the movement model (docs/evaluation.md)");
  return use;
}

void requireTuningSeeds(SeedUse use, const std::string& what) {
  if (use == SeedUse::TrialEvaluation)
    throw Error(what + " looks inside trials, which only tuning seeds (" +
                rangeText(SeedUse::TrialTuning) + ") are for; evaluation seeds (" +
                rangeText(SeedUse::TrialEvaluation) +
                ") give reported figures and are run once, unseen (docs/evaluation.md)");
}

}  // namespace horopter::eval
