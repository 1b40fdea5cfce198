// `horopter eval-interaction`: the paper's Table III on synthetic trials,
// detection over the full image vs inside the horopter's region.
#include <cstdio>
#include <iostream>
#include <map>
#include <string>

#include "command_options.hpp"
#include "commands.hpp"
#include "eval/interaction_report.hpp"
#include "eval/seed_ranges.hpp"
#include "horopter/core/error.hpp"
#include "horopter/eval/interaction_eval.hpp"
#include "horopter/eval/movement_training.hpp"
#include "json_text.hpp"
#include "option_checks.hpp"
#include "report_format.hpp"
#include "shared_options.hpp"

namespace horopter::cli {

namespace {

void printRow(const char* name, const InteractionScopeResult& r) {
  const eval::InteractionIntervals ci = eval::interactionIntervals(r);
  std::printf("%-16s %9d %19s %19s %19s %19s %8d/%-3zu %8.1f %8.1f\n", name, r.movements.segments,
              interval(ci.trackerLoss).c_str(), interval(ci.classification).c_str(),
              interval(ci.realClassification).c_str(), interval(ci.frameTrackerLoss).c_str(),
              r.trialsLostAll(), r.trials.size(), r.visionFps(), r.tracking.fps());
}

void printWorst(const char* name, const InteractionScopeResult& r) {
  std::printf("%s, worst trials (seed: lost/movements, frame loss):", name);
  for (const InteractionTrial* t : eval::worstInteractionTrials(r, 5))
    std::printf("  %llu: %d/%d, %.1f%%", static_cast<unsigned long long>(t->seed),
                t->movements.lost, t->movements.segments, 100.0 * t->tracking.trackerLoss());
  std::printf("\n");
}

// Every trial that lost more than one movement, with the first cause of its
// losses that holds (trialFailureCause), then the causes counted.
void printFailures(std::FILE* out, const char* name, const InteractionScopeResult& r,
                   double framesPerSecond) {
  std::map<std::string, int> byCause;
  std::fprintf(out, "%s, trials that lost more than one movement:\n", name);
  for (const InteractionTrial& t : r.trials) {
    if (t.movements.lost <= 1) continue;
    const TrialDiagnosis& d = t.diagnosis;
    const std::string cause = trialFailureCause(d, framesPerSecond);
    ++byCause[cause];
    std::fprintf(out,
                 "  seed %llu: lost %d/%d movements, frame loss %.1f%%, elected at frame %lld "
                 "(truth %lld), %d release(s); cause %s; lost frames by part:cause",
                 static_cast<unsigned long long>(t.seed), t.movements.lost, t.movements.segments,
                 100.0 * t.tracking.trackerLoss(), static_cast<long long>(d.trackerElectedFrame),
                 static_cast<long long>(d.truthElectedFrame), d.releases, cause.c_str());
    static const char* const kParts[3] = {"head", "left", "right"};
    for (int part = 0; part < 3; ++part)
      for (int c = 0; c < static_cast<int>(LossCause::Count); ++c)
        if (d.causes.counts[part][c] > 0)
          std::fprintf(out, " %s:%s %lld", kParts[part], lossCauseName(static_cast<LossCause>(c)),
                       static_cast<long long>(d.causes.counts[part][c]));
    std::fprintf(out, "\n");
  }
  std::fprintf(out, "%s, failed trials by cause:", name);
  for (const auto& [cause, count] : byCause)
    std::fprintf(out, "  %s %d", cause.c_str(), count);
  std::fprintf(out, "\n");
}

constexpr CommandOption kOptions[] = {
    {.kind = OptionKind::Integer,
     .flag = "--trials",
     .value = "N",
     .min = 1,
     .max = 10000,
     .fallback = "20",
     .help = "trials"},
    {.kind = OptionKind::Integer,
     .flag = "--seed",
     .value = "S",
     .min = 0,
     .max = 1000000000,
     .fallback = "1",
     .help = "first trial's seed"},
    {.kind = OptionKind::Integer,
     .flag = "--frames",
     .value = "F",
     .min = 30,
     .max = 100000,
     .fallback = "300",
     .help = "frames per trial (300: 10 s at 30 frames/s)"},
    {.kind = OptionKind::Text,
     .flag = "--model",
     .value = "FILE",
     .help = "the movement model (default: trained in-process, seconds)"},
    {.kind = OptionKind::Integer,
     .flag = "--grace-frames",
     .value = "N",
     .min = 0,
     .max = 300,
     .fallback = "15",
     .help = "frames after a movement's end where its decision counts"},
    {.kind = OptionKind::Text,
     .flag = "--size",
     .value = "WxH",
     .fallback = "640x480",
     .help = "image size, 64x48..4096x4096"},
    kTrialScopeOption,
    kTrialThreadsOption,
    kBackendOption,
    kTrialJobsOption,
    {.kind = OptionKind::Switch,
     .flag = "--diagnose",
     .help = "list every trial that lost more than one movement with the first cause that "
             "holds: never-elected, released (the godfather lost), elected-late (over 1 s after "
             "the truth), or the part and cause with the most lost frames (see horopter "
             "eval-tracking --diagnose); tuning seeds only"},
    {.kind = OptionKind::Text,
     .flag = "--write-tracks",
     .value = "DIR",
     .help = "write each trial's tracked body with the truth to DIR/<scope>_<seed>.csv (for "
             "horopter classify --track)"},
    {.kind = OptionKind::Switch,
     .flag = "--json",
     .help = "one JSON object: seeds, frames, and {\"full\": {...}, \"roi\": {...}}, each with "
             "percentages 0-100 (tracker_loss, classification_rate, real_classification_rate, "
             "frame_tracker_loss, each with its _ci95 [low, high]), the counts, "
             "trials_lost_all, worst_trials, per_trial (every trial's outcome) and timing "
             "(frames/s and stage times: the only part that depends on the machine)"},
    {.kind = OptionKind::Switch,
     .flag = "--require-region-better",
     .help = "exit 1 unless the region's real classification rate beats the full image's "
             "(needs --scope both)"},
};

}  // namespace

int runEvalInteraction(Args& args) {
  if (args.flag("--help") || args.flag("-h")) {
    std::cout
        << "Usage: horopter eval-interaction [--trials N] [--seed S] [--json] [options]\n\n"
           "The paper's Table III: runs the whole pipeline (synthetic capture closed loop with\n"
           "the head -> rectify -> disparity -> mask -> face and hand detection -> godfather\n"
           "election and tracking -> head control -> LMA features, movement classifier and\n"
           "behaviour) on N synthetic trials, twice: detection over the full image and inside\n"
           "the horopter's region. Trial i uses seed S + i (see horopter eval-tracking for what\n"
           "the seed varies). The main person walks in and performs circle, pointing, wave\n"
           "left, wave right, sagittal wave and bye-bye in turn.\n\n"
           "Scored per movement performed while the main person is the godfather by the truth:\n"
           "  loss%      tracker loss: movements during which the tracker was off the godfather\n"
           "             (no godfather, or a visible part untracked or further than max(20 px,\n"
           "             half a face) from the truth) for at least half of the frames\n"
           "  class%     classification rate: the first decision from the movement's start to\n"
           "             its end + the grace frames is the right movement, among movements\n"
           "             with the tracker on\n"
           "  real%      real classification rate: the same over all movements (a lost tracker\n"
           "             counts as a miss)\n"
           "  frame-loss% eval-tracking's per-frame tracker loss; spurious: decisions outside\n"
           "             every movement\n"
           "  fps        the pipeline without the synthetic renderer: 1000 / the sum of every\n"
           "             stage's mean ms (one frame through every stage, one at a time)\n"
           "  e2e fps    frames per second of the whole run, rendering included\n"
           "  move ms    the movement stage, ms per frame\n\n"
           "Each rate comes with its 95 % confidence interval (percentile bootstrap over\n"
           "trials, 4000 resamples), with the trials that lost every movement (lost-all) and\n"
           "the five worst trials.\n\n"
           "Seeds (docs/evaluation.md): trials take seeds from the tuning range 0-499999 or the\n"
           "evaluation range 500000-999999, never both; the movement model was trained on\n"
           "1000000.. and tuned on 2000000... A reported figure comes from a fresh block of at\n"
           "least 100 evaluation seeds, run once; --write-tracks (a look inside the trials) is\n"
           "refused on evaluation seeds.\n\n"
           "Options:\n"
        << commandOptionsHelp(kOptions);
    return 0;
  }
  const CommandOptions opts(args, kOptions);
  args.finish("eval-interaction");
  InteractionEvalOptions options;
  options.trials = static_cast<int>(opts.integer("--trials"));
  const int seed = static_cast<int>(opts.integer("--seed"));
  options.trial.frames = static_cast<int>(opts.integer("--frames"));
  const std::string modelPath = opts.text("--model");
  options.graceFrames = static_cast<int>(opts.integer("--grace-frames"));
  const std::string scopeName = opts.text("--scope");
  const ImageSize wh = parseImageSize(opts.text("--size"), "--size", {64, 48}, {4096, 4096});
  options.trial.width = wh.width;
  options.trial.height = wh.height;
  options.trial.threads = static_cast<int>(opts.integer("--threads"));
  options.trial.backend = opts.text("--backend");
  options.jobs = static_cast<int>(opts.integer("--jobs"));
  options.writeTracksDir = opts.text("--write-tracks");
  options.diagnose = opts.on("--diagnose");
  const bool json = opts.on("--json");
  const bool requireBetter = opts.on("--require-region-better");
  if (requireBetter && scopeName != "both")
    throw UsageError("--require-region-better needs --scope both");
  options.trial.seed = static_cast<std::uint64_t>(seed);
  const eval::SeedUse seedUse = asUsageError(
      [&] { return eval::trialSeedUse(options.trial.seed, options.trials, "--seed"); });
  if (!options.writeTracksDir.empty())
    asUsageError([&] { eval::requireTuningSeeds(seedUse, "--write-tracks"); });
  if (options.diagnose) asUsageError([&] { eval::requireTuningSeeds(seedUse, "--diagnose"); });
  if (!modelPath.empty()) requireFile(modelPath, "movement model");
  requireBackend(options.trial.backend);
  if (!options.writeTracksDir.empty())
    requireWritableFolder(options.writeTracksDir, "--write-tracks");
  options.model = loadOrTrainMovementModel(modelPath);
  options.progress = [&](DetectionScope scope, int i, const MovementScore& s) {
    std::fprintf(stderr, "%s trial %d/%d (seed %llu): %d movements, %d lost, %d right\n",
                 detectionScopeName(scope), i + 1, options.trials,
                 static_cast<unsigned long long>(options.trial.seed + i), s.segments, s.lost,
                 s.correctTracked);
  };

  InteractionScopeResult full, roi;
  const bool runFull = scopeName != "region", runRoi = scopeName != "full";
  if (runFull) full = evaluateInteraction(options, DetectionScope::FullImage);
  if (runRoi) roi = evaluateInteraction(options, DetectionScope::HoropterRegion);
  const bool better =
      roi.movements.realClassificationPct() > full.movements.realClassificationPct();
  if (json) {
    eval::Json out{{"seed_use", eval::seedUseName(seedUse)},
                   {"trials", options.trials},
                   {"seed_first", seed},
                   {"seed_last", seed + options.trials - 1},
                   {"frames", options.trial.frames},
                   {"width", options.trial.width},
                   {"height", options.trial.height}};
    if (runFull) out["full"] = eval::interactionScopeJson(full);
    if (runRoi) out["roi"] = eval::interactionScopeJson(roi);
    writeJsonLine(detail::jsonText(out));
  } else {
    std::printf("%d trials (seeds %d-%d, %s), %d frames each at %dx%d\n", options.trials, seed,
                seed + options.trials - 1, eval::seedUseName(seedUse), options.trial.frames,
                options.trial.width, options.trial.height);
    std::printf("%-16s %9s %19s %19s %19s %19s %12s %8s %8s\n", "scope", "movements",
                "loss% [95% CI]", "class% [95% CI]", "real% [95% CI]", "frame-loss% [CI]",
                "lost-all", "fps", "e2e fps");
    if (runFull) printRow("full-image", full);
    if (runRoi) printRow("horopter-region", roi);
    if (runFull) printWorst("full-image", full);
    if (runRoi) printWorst("horopter-region", roi);
    if (runFull && runRoi)
      std::printf("region vs full image: real classification %s\n",
                  better ? "higher" : "NOT higher");
    std::printf("%s\n", reportability(seedUse, options.trials).c_str());
  }
  if (options.diagnose) {
    const double fps = trialScene(options.trial).framesPerSecond;
    if (runFull) printFailures(json ? stderr : stdout, "full-image", full, fps);
    if (runRoi) printFailures(json ? stderr : stdout, "horopter-region", roi, fps);
  }
  if (requireBetter && !better) {
    std::cerr << "horopter eval-interaction: the region's real classification rate ("
              << roi.movements.realClassificationPct() << " %) does not beat the full image's ("
              << full.movements.realClassificationPct() << " %)\n";
    return 1;
  }
  return 0;
}

}  // namespace horopter::cli
