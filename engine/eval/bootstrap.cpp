// See bootstrap.hpp.
#include "eval/bootstrap.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "horopter/core/error.hpp"
#include "synthetic/rng.hpp"

namespace horopter::eval {

RatioEstimate bootstrapRatio(std::span<const double> numerators,
                             std::span<const double> denominators, double level, int resamples,
                             std::uint64_t seed) {
  if (numerators.size() != denominators.size())
    throw Error("bootstrap: one numerator and one denominator per trial");
  if (!(level > 0 && level < 1)) throw Error("bootstrap: the level must lie within (0, 1)");
  if (resamples < 1) throw Error("bootstrap: at least one resample");
  RatioEstimate e;
  e.level = level;
  double num = 0, den = 0;
  for (std::size_t i = 0; i < numerators.size(); ++i)
    num += numerators[i], den += denominators[i];
  e.value = den != 0 ? num / den : 0;
  const std::size_t n = numerators.size();
  if (n == 0) return e;
  synth::SplitMix64 rng(seed);
  std::vector<double> ratios;
  ratios.reserve(static_cast<std::size_t>(resamples));
  for (int r = 0; r < resamples; ++r) {
    double rn = 0, rd = 0;
    for (std::size_t k = 0; k < n; ++k) {
      // Multiply-shift: an index uniform in [0, n) from 32 random bits.
      const std::size_t i = static_cast<std::size_t>(((rng.next() >> 32) * n) >> 32);
      rn += numerators[i];
      rd += denominators[i];
    }
    if (rd != 0) ratios.push_back(rn / rd);  // a resample with nothing to rate says nothing
  }
  e.resamples = static_cast<int>(ratios.size());
  if (ratios.empty()) return e;
  std::sort(ratios.begin(), ratios.end());
  const double tail = 0.5 * (1 - level);
  const auto at = [&](double q) {
    const double pos = q * static_cast<double>(ratios.size() - 1);
    return ratios[static_cast<std::size_t>(std::lround(pos))];
  };
  e.low = at(tail);
  e.high = at(1 - tail);
  return e;
}

}  // namespace horopter::eval
