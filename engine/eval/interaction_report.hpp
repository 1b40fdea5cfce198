// Table III as JSON (horopter eval-interaction --json, and the distributed
// evaluation in Python): each scope's figures with 95 % bootstrap intervals
// over trials, how many trials lost all their movements, the worst trials,
// and every trial's outcome. What depends on the machine (frames/s, stage
// times) sits under "timing", so two runs of the same trials compare equal
// once "timing" is removed, wherever they ran.
#pragma once

#include <nlohmann/json.hpp>

#include "eval/bootstrap.hpp"
#include "horopter/eval/interaction_eval.hpp"

namespace horopter::eval {

using Json = nlohmann::ordered_json;

// One trial, complete enough to be summed again (interactionTrialFromJson).
Json interactionTrialJson(const InteractionTrial& trial);
// Throws horopter::Error naming the key that is missing or of the wrong type.
InteractionTrial interactionTrialFromJson(const Json& json);

// A scope's figures, intervals, worst trials and per-trial outcomes.
Json interactionScopeJson(const InteractionScopeResult& result, int worstTrials = 5);

// The trials, worst first: most movements lost, then the highest per-frame
// tracker loss, then the lowest seed.
std::vector<const InteractionTrial*> worstInteractionTrials(const InteractionScopeResult& result,
                                                            int count);

// The three per-movement rates and the frame loss with their intervals, in
// percent: {value, low, high}.
struct InteractionIntervals {
  RatioEstimate trackerLoss, classification, realClassification, frameTrackerLoss;
};
InteractionIntervals interactionIntervals(const InteractionScopeResult& result);

}  // namespace horopter::eval
