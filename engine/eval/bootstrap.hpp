// Confidence intervals over trials: the percentile bootstrap of a ratio of
// sums (lost movements / movements, lost frames / godfather frames, ...).
// Trials are the unit that is resampled, because a trial's frames and
// movements are not independent of each other: a closed-loop trial that
// goes wrong loses many at once.
#pragma once

#include <cstdint>
#include <span>

namespace horopter::eval {

struct RatioEstimate {
  double value = 0;          // sum(numerators) / sum(denominators); 0 when that is 0
  double low = 0, high = 0;  // the interval's bounds
  double level = 0.95;       // its confidence level
  int resamples = 0;         // resamples with a non-zero denominator
};

// Resamples the trials `resamples` times (with replacement, from a fixed
// seed: the same interval on every run and platform). Both spans have one
// value per trial. Throws horopter::Error when their sizes differ or the
// level is not within (0, 1).
RatioEstimate bootstrapRatio(std::span<const double> numerators,
                             std::span<const double> denominators, double level = 0.95,
                             int resamples = 4000, std::uint64_t seed = 20261201);

}  // namespace horopter::eval
