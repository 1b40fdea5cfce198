// See interaction_report.hpp.
#include "eval/interaction_report.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include "horopter/core/error.hpp"

namespace horopter::eval {

namespace {

RatioEstimate percent(RatioEstimate e) {
  e.value *= 100;
  e.low *= 100;
  e.high *= 100;
  return e;
}

Json estimateJson(const RatioEstimate& e) {
  return Json::array({e.low, e.high});
}

// A required member of `json`, converted; the error names the key.
template <class T>
T member(const Json& json, const char* key) {
  if (!json.is_object() || !json.contains(key))
    throw Error(std::string("interaction trial JSON: missing \"") + key + "\"");
  try {
    return json.at(key).get<T>();
  } catch (const nlohmann::json::exception&) {
    throw Error(std::string("interaction trial JSON: \"") + key + "\" has the wrong type");
  }
}

Json partJson(const PartScore& p) {
  return Json{{"visible", p.visible}, {"lost", p.lost}};
}
PartScore partFromJson(const Json& j) {
  return PartScore{member<std::int64_t>(j, "visible"), member<std::int64_t>(j, "lost")};
}

DetectionScope scopeFromName(const std::string& name) {
  if (name == detectionScopeName(DetectionScope::HoropterRegion))
    return DetectionScope::HoropterRegion;
  if (name == detectionScopeName(DetectionScope::FullImage)) return DetectionScope::FullImage;
  throw Error("interaction trial JSON: unknown scope '" + name + "'");
}

double frameLossPct(const InteractionTrial& t) {
  return 100.0 * t.tracking.trackerLoss();
}

}  // namespace

Json interactionTrialJson(const InteractionTrial& t) {
  const TrialResult& r = t.tracking;
  Json stages = Json::array();
  for (const StageSummary& s : r.summary.stages)
    stages.push_back(Json{{"name", s.name}, {"frames", s.frames}, {"mean_ms", s.meanMs}});
  return Json{{"seed", t.seed},
              {"scope", detectionScopeName(r.scope)},
              {"movements", t.movements.segments},
              {"lost", t.movements.lost},
              {"correct", t.movements.correct},
              {"correct_tracked", t.movements.correctTracked},
              {"spurious", t.movements.spurious},
              {"lost_all", t.lostAll()},
              {"frames", r.frames},
              {"godfather_frames", r.godfatherFrames},
              {"lost_frames", r.lostFrames},
              {"frame_tracker_loss", frameLossPct(t)},
              {"head", partJson(r.head)},
              {"left_hand", partJson(r.leftHand)},
              {"right_hand", partJson(r.rightHand)},
              {"detections", r.detections},
              {"false_detections", r.falseDetections},
              {"timing", Json{{"captured", r.summary.captured},
                              {"completed", r.summary.completed},
                              {"dropped", r.summary.dropped},
                              {"seconds", r.summary.seconds},
                              {"mean_latency_ms", r.summary.meanLatencyMs},
                              {"max_latency_ms", r.summary.maxLatencyMs},
                              {"stages", stages}}}};
}

InteractionTrial interactionTrialFromJson(const Json& j) {
  InteractionTrial t;
  t.seed = member<std::uint64_t>(j, "seed");
  t.movements.segments = member<int>(j, "movements");
  t.movements.lost = member<int>(j, "lost");
  t.movements.correct = member<int>(j, "correct");
  t.movements.correctTracked = member<int>(j, "correct_tracked");
  t.movements.spurious = member<int>(j, "spurious");
  TrialResult& r = t.tracking;
  r.seed = t.seed;
  r.scope = scopeFromName(member<std::string>(j, "scope"));
  r.frames = member<std::int64_t>(j, "frames");
  r.godfatherFrames = member<std::int64_t>(j, "godfather_frames");
  r.lostFrames = member<std::int64_t>(j, "lost_frames");
  r.head = partFromJson(member<Json>(j, "head"));
  r.leftHand = partFromJson(member<Json>(j, "left_hand"));
  r.rightHand = partFromJson(member<Json>(j, "right_hand"));
  r.detections = member<std::int64_t>(j, "detections");
  r.falseDetections = member<std::int64_t>(j, "false_detections");
  const Json timing = member<Json>(j, "timing");
  r.summary.captured = member<std::int64_t>(timing, "captured");
  r.summary.completed = member<std::int64_t>(timing, "completed");
  r.summary.dropped = member<std::int64_t>(timing, "dropped");
  r.summary.seconds = member<double>(timing, "seconds");
  r.summary.meanLatencyMs = member<double>(timing, "mean_latency_ms");
  r.summary.maxLatencyMs = member<double>(timing, "max_latency_ms");
  const Json stages = member<Json>(timing, "stages");
  if (!stages.is_array()) throw Error("interaction trial JSON: \"stages\" is not an array");
  for (const Json& s : stages)
    r.summary.stages.push_back(StageSummary{member<std::string>(s, "name"),
                                            member<std::int64_t>(s, "frames"),
                                            member<double>(s, "mean_ms")});
  if (t.movements.lost > t.movements.segments || r.lostFrames > r.godfatherFrames)
    throw Error("interaction trial JSON: more lost than counted (seed " + std::to_string(t.seed) +
                ")");
  return t;
}

std::vector<const InteractionTrial*> worstInteractionTrials(const InteractionScopeResult& result,
                                                            int count) {
  std::vector<const InteractionTrial*> order;
  for (const InteractionTrial& t : result.trials)
    order.push_back(&t);
  std::stable_sort(order.begin(), order.end(), [](const auto* a, const auto* b) {
    if (a->movements.lost != b->movements.lost) return a->movements.lost > b->movements.lost;
    if (frameLossPct(*a) != frameLossPct(*b)) return frameLossPct(*a) > frameLossPct(*b);
    return a->seed < b->seed;
  });
  order.resize(std::min(order.size(), static_cast<std::size_t>(std::max(0, count))));
  return order;
}

InteractionIntervals interactionIntervals(const InteractionScopeResult& result) {
  std::vector<double> lost, segments, correctTracked, tracked, lostFrames, godfatherFrames;
  for (const InteractionTrial& t : result.trials) {
    lost.push_back(t.movements.lost);
    segments.push_back(t.movements.segments);
    correctTracked.push_back(t.movements.correctTracked);
    tracked.push_back(t.movements.segments - t.movements.lost);
    lostFrames.push_back(static_cast<double>(t.tracking.lostFrames));
    godfatherFrames.push_back(static_cast<double>(t.tracking.godfatherFrames));
  }
  InteractionIntervals i;
  i.trackerLoss = percent(bootstrapRatio(lost, segments));
  i.classification = percent(bootstrapRatio(correctTracked, tracked));
  i.realClassification = percent(bootstrapRatio(correctTracked, segments));
  i.frameTrackerLoss = percent(bootstrapRatio(lostFrames, godfatherFrames));
  return i;
}

Json interactionScopeJson(const InteractionScopeResult& r, int worstTrials) {
  const InteractionIntervals ci = interactionIntervals(r);
  Json worst = Json::array();
  for (const InteractionTrial* t : worstInteractionTrials(r, worstTrials))
    worst.push_back(Json{{"seed", t->seed},
                         {"movements", t->movements.segments},
                         {"lost", t->movements.lost},
                         {"frame_tracker_loss", frameLossPct(*t)}});
  Json trials = Json::array();
  for (const InteractionTrial& t : r.trials)
    trials.push_back(interactionTrialJson(t));
  return Json{{"scope", detectionScopeName(r.scope)},
              {"trials", r.trials.size()},
              {"seed_first", r.trials.empty() ? 0 : r.trials.front().seed},
              {"seed_last", r.trials.empty() ? 0 : r.trials.back().seed},
              {"tracker_loss", r.movements.trackerLossPct()},
              {"tracker_loss_ci95", estimateJson(ci.trackerLoss)},
              {"classification_rate", r.movements.classificationPct()},
              {"classification_rate_ci95", estimateJson(ci.classification)},
              {"real_classification_rate", r.movements.realClassificationPct()},
              {"real_classification_rate_ci95", estimateJson(ci.realClassification)},
              {"frame_tracker_loss", 100.0 * r.tracking.trackerLoss()},
              {"frame_tracker_loss_ci95", estimateJson(ci.frameTrackerLoss)},
              {"movements", r.movements.segments},
              {"lost", r.movements.lost},
              {"correct", r.movements.correctTracked},
              {"spurious", r.movements.spurious},
              {"trials_lost_all", r.trialsLostAll()},
              {"worst_trials", worst},
              {"per_trial", trials},
              {"timing", Json{{"fps", r.visionFps()},
                              {"end_to_end_fps", r.tracking.fps()},
                              {"detection_ms", r.tracking.detectionMs},
                              {"movement_ms", r.movementMs}}}};
}

}  // namespace horopter::eval
