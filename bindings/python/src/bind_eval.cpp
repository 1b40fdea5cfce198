// Table III one trial at a time, for evaluations spread over many machines
// (scripts/eval_cluster.py drives these through Dask): a worker runs
// interaction_trial for a seed and returns its outcome as JSON; the client
// sums the outcomes with interaction_summary, in seed order, exactly as
// `horopter eval-interaction` sums its own.
#include <pybind11/stl.h>

#include <string>
#include <vector>

#include "bindings.hpp"
#include "eval/interaction_report.hpp"
#include "eval/seed_ranges.hpp"
#include "horopter/core/error.hpp"
#include "horopter/eval/interaction_eval.hpp"
#include "horopter/eval/movement_training.hpp"

namespace horopter::python {

namespace {

DetectionScope scopeFrom(const std::string& name) {
  if (name == "region") return DetectionScope::HoropterRegion;
  if (name == "full") return DetectionScope::FullImage;
  throw Error("scope takes 'region' or 'full', got '" + name + "'");
}

std::string interactionTrial(std::uint64_t seed, const std::string& scope, int frames, int width,
                             int height, int graceFrames, const std::string& modelPath) {
  // The same checks and defaults as `horopter eval-interaction`.
  eval::trialSeedUse(seed, 1, "seed");
  if (frames < 30 || frames > 100000) throw Error("frames must be within 30..100000");
  if (width < 64 || height < 48 || width > 4096 || height > 4096)
    throw Error("width x height must lie within 64x48..4096x4096");
  if (graceFrames < 0 || graceFrames > 300) throw Error("grace_frames must be within 0..300");
  InteractionEvalOptions options;
  options.trial.seed = seed;
  options.trial.frames = frames;
  options.trial.width = width;
  options.trial.height = height;
  options.graceFrames = graceFrames;
  options.model = loadOrTrainMovementModel(modelPath);
  return eval::interactionTrialJson(runInteractionTrial(options, scopeFrom(scope), 0)).dump();
}

std::string interactionSummary(const std::vector<std::string>& trials, const std::string& scope) {
  std::vector<InteractionTrial> parsed;
  parsed.reserve(trials.size());
  for (const std::string& text : trials) {
    const eval::Json json = eval::Json::parse(text, nullptr, /*allow_exceptions=*/false);
    if (json.is_discarded()) throw Error("interaction_summary: a trial is not valid JSON");
    parsed.push_back(eval::interactionTrialFromJson(json));
  }
  const DetectionScope s = scopeFrom(scope);
  for (const InteractionTrial& t : parsed)
    if (t.tracking.scope != s)
      throw Error("interaction_summary: trial " + std::to_string(t.seed) + " ran in another scope");
  return eval::interactionScopeJson(summariseInteraction(s, std::move(parsed))).dump();
}

}  // namespace

void bindEval(py::module_& m) {
  m.def(
      "seed_use",
      [](std::uint64_t first, std::int64_t count) {
        return std::string(eval::seedUseName(eval::trialSeedUse(first, count, "seed")));
      },
      py::arg("first"), py::arg("count") = 1,
      "'tuning' or 'evaluation': the range trial seeds first..first+count-1 lie in "
      "(docs/evaluation.md); horopter.Error when they straddle ranges or leave the trial ranges");
  m.def("interaction_trial", &interactionTrial, py::arg("seed"), py::arg("scope") = "region",
        py::arg("frames") = 300, py::arg("width") = 640, py::arg("height") = 480,
        py::arg("grace_frames") = 15, py::arg("model_path") = "",
        py::call_guard<py::gil_scoped_release>(),
        "Runs one trial of `horopter eval-interaction` (seed, scope 'region' or 'full') and "
        "returns its outcome as a JSON string (the 'per_trial' entries of --json). model_path "
        "'' is the default model, trained in-process on first use.");
  m.def("interaction_summary", &interactionSummary, py::arg("trials"), py::arg("scope"),
        "Sums trial outcomes (JSON strings from interaction_trial, in seed order) into the "
        "scope's figures: the JSON string of `horopter eval-interaction --json`'s 'roi' or "
        "'full' entry.");
}

}  // namespace horopter::python
