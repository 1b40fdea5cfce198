// The Bayesian movement classifier: a discrete hidden Markov model over the
// movement, with the LMA symbols as its per-frame evidence.
//
// Model structure
// ---------------
// Variables, per frame t:
//   M_t        hidden: the movement being performed, one of the seven
//              MovementClass values (none and the six of Table II)
//   F_t^1..15  observed: the LMA symbols of LmaFeatures::symbols (lma.hpp):
//              active hand, the displacement sector in the frontal, sagittal
//              and horizontal planes, speed, curvature, hand height, lateral
//              position and reach, incentre rise, perimeter change, Body,
//              Effort Time, Space and Flow
// Dependencies:
//   M_t depends on M_{t-1} only:  P(M_t = M_{t-1}) = stay,
//                                 P(M_t = m' != M_{t-1}) = (1 - stay) / 6
//   each F_t^k depends on M_t only (naive Bayes given the movement), with a
//   categorical table P(F^k = v | M = m) learned by counting labelled frames.
//   Successive frames' symbols are far from independent (they come from
//   overlapping windows), so each frame's likelihood enters with an exponent
//   evidenceWeight < 1 (a tempered likelihood).
// Priors:
//   P(M_0): the labelled frames' class frequencies (Dirichlet-smoothed);
//   P(F^k | M): a symmetric Dirichlet(alpha) prior on every table, so a value
//   never seen in training keeps a small probability.
// Inference: the forward filter, P(M_t | F_1..t) ∝ P(F_t | M_t)^w
//   Σ_m P(M_t | M_{t-1} = m) P(M_{t-1} = m | F_1..t-1). Frames without valid
//   features apply the transition only. A decision is made when a movement's
//   posterior passes decisionThreshold; that movement can be decided again
//   once its posterior has fallen below rearmThreshold.
//
// File format (text, one record per line, '#' lines ignored):
//   horopter-movement-model 1
//   params <stay> <evidenceWeight> <decisionThreshold> <rearmThreshold> <alpha>
//   classes none circle pointing wave-left wave-right sagittal-wave bye-bye
//   frames <count per class>
//   symbol <name> <cardinality>
//   counts <value> <count per class>      (cardinality lines after each symbol)
//   end
// Counts, not probabilities, are stored, so a model reloads to exactly the
// same tables and posteriors.
#pragma once

#include "horopter/core/export.hpp"

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "horopter/movement/lma.hpp"
#include "horopter/movement/movement.hpp"

namespace horopter {

struct HOROPTER_API MovementModelParams {
  double stay = 0.97;               // P(M_t = M_{t-1}), in (0, 1)
  double evidenceWeight = 0.15;     // exponent of each frame's likelihood, in (0, 1]
  double decisionThreshold = 0.95;  // posterior to decide a movement, in (0.5, 1)
  double rearmThreshold = 0.3;      // posterior below which it can be decided again
  double alpha = 1.0;               // Dirichlet prior of every table, > 0
};

// Labelled symbol counts: what training produces and the file stores.
struct HOROPTER_API MovementCounts {
  // [symbol][value][class]
  std::array<std::vector<std::array<std::int64_t, kMovementClassCount>>, kLmaSymbolCount> table;
  std::array<std::int64_t, kMovementClassCount> frames{};  // labelled frames per class

  MovementCounts();  // zero counts, each symbol sized by its cardinality
  void add(MovementClass label, const LmaFeatures& features);  // ignores invalid features
  void merge(const MovementCounts& other);
};

class HOROPTER_API MovementModel {
 public:
  static constexpr int kFormatVersion = 1;
  static constexpr const char* kMagic = "horopter-movement-model";

  // Throws horopter::Error for parameters out of range.
  MovementModel(MovementCounts counts, MovementModelParams params);

  const MovementCounts& counts() const { return counts_; }
  const MovementModelParams& params() const { return params_; }
  double logPrior(MovementClass m) const { return logPrior_[static_cast<int>(m)]; }
  // log P(F^symbol = value | M = m).
  double logLikelihood(int symbol, int value, MovementClass m) const {
    return logTable_[symbol][value][static_cast<int>(m)];
  }
  // The same counts with other parameters (for tuning).
  MovementModel withParams(MovementModelParams params) const;

  std::string serialize() const;
  // Throws horopter::Error naming `source` and the line for anything wrong:
  // another file type, another version, a missing or malformed record.
  static MovementModel parse(const std::string& text, const std::string& source);
  void save(const std::string& path) const;
  static MovementModel load(const std::string& path);

 private:
  MovementCounts counts_;
  MovementModelParams params_;
  std::array<double, kMovementClassCount> logPrior_{};
  std::array<std::vector<std::array<double, kMovementClassCount>>, kLmaSymbolCount> logTable_;
};

// The online filter and the decision rule.
class HOROPTER_API MovementClassifier {
 public:
  explicit MovementClassifier(std::shared_ptr<const MovementModel> model);

  struct Step {
    MovementPosterior posterior{};
    MovementClass likeliest = MovementClass::None;
    std::optional<MovementClass> decision;
  };
  Step update(const LmaFeatures& features);
  void reset();  // back to the prior, every movement armed
  const MovementModel& model() const { return *model_; }

 private:
  std::shared_ptr<const MovementModel> model_;
  MovementPosterior posterior_{};
  std::array<bool, kMovementClassCount> armed_{};
};

}  // namespace horopter
