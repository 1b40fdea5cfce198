// The movement model's tables and the forward filter; see
// include/horopter/movement/movement_classifier.hpp for the model's structure.
#include "horopter/movement/movement_classifier.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "horopter/core/error.hpp"

namespace horopter {

namespace {

void checkParams(const MovementModelParams& p) {
  auto bad = [](const std::string& what) { throw Error("movement model: " + what); };
  if (!(p.stay > 0 && p.stay < 1)) bad("stay must be in (0, 1), got " + std::to_string(p.stay));
  if (!(p.evidenceWeight > 0 && p.evidenceWeight <= 1))
    bad("evidence weight must be in (0, 1], got " + std::to_string(p.evidenceWeight));
  if (!(p.decisionThreshold > 0.5 && p.decisionThreshold < 1))
    bad("decision threshold must be in (0.5, 1), got " + std::to_string(p.decisionThreshold));
  if (!(p.rearmThreshold >= 0 && p.rearmThreshold < p.decisionThreshold))
    bad("re-arm threshold must be in [0, decision threshold), got " +
        std::to_string(p.rearmThreshold));
  if (!(p.alpha > 0 && std::isfinite(p.alpha)))
    bad("alpha must be positive, got " + std::to_string(p.alpha));
}

}  // namespace

MovementCounts::MovementCounts() {
  for (int s = 0; s < kLmaSymbolCount; ++s)
    table[s].assign(lmaSymbolCardinality(static_cast<LmaSymbol>(s)), {});
}

void MovementCounts::add(MovementClass label, const LmaFeatures& features) {
  if (!features.valid) return;
  const int m = static_cast<int>(label);
  ++frames[m];
  for (int s = 0; s < kLmaSymbolCount; ++s)
    ++table[s][features.symbols[s]][m];
}

void MovementCounts::merge(const MovementCounts& other) {
  for (int m = 0; m < kMovementClassCount; ++m)
    frames[m] += other.frames[m];
  for (int s = 0; s < kLmaSymbolCount; ++s)
    for (std::size_t v = 0; v < table[s].size(); ++v)
      for (int m = 0; m < kMovementClassCount; ++m)
        table[s][v][m] += other.table[s][v][m];
}

MovementModel::MovementModel(MovementCounts counts, MovementModelParams params)
    : counts_(std::move(counts)), params_(params) {
  checkParams(params_);
  const double a = params_.alpha;
  double total = 0;
  for (auto c : counts_.frames)
    total += static_cast<double>(c);
  for (int m = 0; m < kMovementClassCount; ++m)
    logPrior_[m] =
        std::log((static_cast<double>(counts_.frames[m]) + a) / (total + a * kMovementClassCount));
  for (int s = 0; s < kLmaSymbolCount; ++s) {
    const auto& t = counts_.table[s];
    const int values = static_cast<int>(t.size());
    logTable_[s].assign(values, {});
    for (int m = 0; m < kMovementClassCount; ++m) {
      double sum = 0;
      for (int v = 0; v < values; ++v)
        sum += static_cast<double>(t[v][m]);
      for (int v = 0; v < values; ++v)
        logTable_[s][v][m] = std::log((static_cast<double>(t[v][m]) + a) / (sum + a * values));
    }
  }
}

MovementModel MovementModel::withParams(MovementModelParams params) const {
  return MovementModel(counts_, params);
}

MovementClassifier::MovementClassifier(std::shared_ptr<const MovementModel> model)
    : model_(std::move(model)) {
  if (!model_) throw Error("movement classifier: no model");
  reset();
}

void MovementClassifier::reset() {
  for (int m = 0; m < kMovementClassCount; ++m)
    posterior_[m] = std::exp(model_->logPrior(static_cast<MovementClass>(m)));
  double sum = 0;
  for (double p : posterior_)
    sum += p;
  for (double& p : posterior_)
    p /= sum;
  armed_.fill(true);
}

MovementClassifier::Step MovementClassifier::update(const LmaFeatures& features) {
  const MovementModelParams& p = model_->params();
  // Predict: the sticky transition.
  const double leave = (1 - p.stay) / (kMovementClassCount - 1);
  MovementPosterior predicted{};
  for (int m = 0; m < kMovementClassCount; ++m)
    predicted[m] = p.stay * posterior_[m] + leave * (1 - posterior_[m]);
  // Update: the tempered likelihood of this frame's symbols.
  std::array<double, kMovementClassCount> logPost{};
  for (int m = 0; m < kMovementClassCount; ++m) {
    double ll = 0;
    if (features.valid)
      for (int s = 0; s < kLmaSymbolCount; ++s)
        ll += model_->logLikelihood(s, features.symbols[s], static_cast<MovementClass>(m));
    logPost[m] = std::log(predicted[m]) + p.evidenceWeight * ll;
  }
  const double top = *std::max_element(logPost.begin(), logPost.end());
  double sum = 0;
  for (int m = 0; m < kMovementClassCount; ++m)
    sum += (posterior_[m] = std::exp(logPost[m] - top));
  for (double& q : posterior_)
    q /= sum;

  Step step;
  step.posterior = posterior_;
  step.likeliest = static_cast<MovementClass>(
      std::max_element(posterior_.begin(), posterior_.end()) - posterior_.begin());
  for (int m = 1; m < kMovementClassCount; ++m) {
    if (posterior_[m] < p.rearmThreshold) armed_[m] = true;
    if (armed_[m] && posterior_[m] >= p.decisionThreshold) {
      step.decision = static_cast<MovementClass>(m);
      armed_[m] = false;
    }
  }
  return step;
}

}  // namespace horopter
