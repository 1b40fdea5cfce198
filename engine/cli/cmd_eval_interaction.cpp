// `horopter eval-interaction`: the paper's Table III on synthetic trials,
// detection over the full image vs inside the horopter's region.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>

#include "commands.hpp"
#include "horopter/error.hpp"
#include "horopter/interaction_eval.hpp"
#include "horopter/movement_training.hpp"

namespace horopter::cli {

namespace {

std::string scopeJson(const InteractionScopeResult& r) {
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "{\"tracker_loss\": %.2f, \"classification_rate\": %.2f, "
                "\"real_classification_rate\": %.2f, \"fps\": %.2f, \"movements\": %d, "
                "\"lost\": %d, \"correct\": %d, \"spurious\": %d, \"frame_tracker_loss\": %.2f, "
                "\"end_to_end_fps\": %.2f, \"movement_ms\": %.4f}",
                r.movements.trackerLossPct(), r.movements.classificationPct(),
                r.movements.realClassificationPct(), r.visionFps(), r.movements.segments,
                r.movements.lost, r.movements.correctTracked, r.movements.spurious,
                100.0 * r.tracking.trackerLoss(), r.tracking.fps(), r.movementMs);
  return buf;
}

void printRow(const char* name, const InteractionScopeResult& r) {
  std::printf("%-16s %9d %8.1f %8.1f %8.1f %10.1f %9d %8.1f %8.1f %9.3f\n", name,
              r.movements.segments, r.movements.trackerLossPct(), r.movements.classificationPct(),
              r.movements.realClassificationPct(), 100.0 * r.tracking.trackerLoss(),
              r.movements.spurious, r.visionFps(), r.tracking.fps(), r.movementMs);
}

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
           "The model was trained on seeds 1000000.. and tuned on 2000000..; use trial seeds\n"
           "below 1000000 for held-out results.\n\n"
           "Options:\n"
           "  --trials N         trials (default 20)\n"
           "  --seed S           first trial's seed (default 1)\n"
           "  --frames F         frames per trial (default 300: 10 s at 30 frames/s)\n"
           "  --model FILE       the movement model (default: trained in-process, seconds)\n"
           "  --grace-frames N   frames after a movement's end where its decision counts\n"
           "                     (default 15)\n"
           "  --size WxH         image size (default 640x480)\n"
           "  --scope S          region, full or both (default both)\n"
           "  --threads N        threads of the disparity stage (default 1)\n"
           "  --backend B        front end backend (default auto)\n"
           "  --jobs N           trials run N at a time (default 1); the rates do not depend\n"
           "                     on it, but fps and e2e fps are then measured with the\n"
           "                     trials competing for the cores\n"
           "  --write-tracks DIR write each trial's tracked body with the truth to\n"
           "                     DIR/<scope>_<seed>.csv (for horopter classify --track)\n"
           "  --json             one JSON object {\"full\": {...}, \"roi\": {...}}, percentages\n"
           "                     0-100: tracker_loss, classification_rate,\n"
           "                     real_classification_rate, fps, and the counts\n"
           "  --require-region-better  exit 1 unless the region's real classification rate\n"
           "                     beats the full image's (needs --scope both)\n";
    return 0;
  }
  InteractionEvalOptions options;
  options.trials = args.intValue("--trials", 20);
  const int seed = args.intValue("--seed", 1);
  options.trial.frames = args.intValue("--frames", 300);
  const std::string modelPath = args.stringValue("--model", "");
  options.graceFrames = args.intValue("--grace-frames", 15);
  const std::string scopeName = args.stringValue("--scope", "both");
  const std::string size = args.stringValue("--size", "640x480");
  options.trial.threads = args.intValue("--threads", 1);
  options.trial.backend = args.stringValue("--backend", "auto");
  options.jobs = args.intValue("--jobs", 1);
  options.writeTracksDir = args.stringValue("--write-tracks", "");
  const bool json = args.flag("--json");
  const bool requireBetter = args.flag("--require-region-better");
  args.finish("eval-interaction");
  if (options.trials < 1 || options.trials > 10000) throw Error("--trials must be within 1..10000");
  if (seed < 0) throw Error("--seed must be >= 0");
  if (options.trial.frames < 30 || options.trial.frames > 100000)
    throw Error("--frames must be within 30..100000");
  if (options.graceFrames < 0 || options.graceFrames > 300)
    throw Error("--grace-frames must be within 0..300");
  if (options.trial.threads < 1 || options.trial.threads > 256)
    throw Error("--threads must be within 1..256");
  if (options.jobs < 1 || options.jobs > 64) throw Error("--jobs must be within 1..64");
  {
    int w = 0, h = 0;
    char x = 0, extra = 0;
    if (std::sscanf(size.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || x != 'x' || w < 64 ||
        h < 48 || w > 4096 || h > 4096)
      throw Error("--size takes WxH within 64x48..4096x4096, got '" + size + "'");
    options.trial.width = w;
    options.trial.height = h;
  }
  if (scopeName != "both" && scopeName != "region" && scopeName != "full")
    throw Error("--scope takes region, full or both, got '" + scopeName + "'");
  if (requireBetter && scopeName != "both")
    throw Error("--require-region-better needs --scope both");
  options.trial.seed = static_cast<std::uint64_t>(seed);
  if (options.trial.seed + options.trials > kEvaluationSeedLimit)
    std::cerr << "warning: trial seeds reach " << kEvaluationSeedLimit
              << " and above, the training and tuning range\n";
  if (!options.writeTracksDir.empty()) std::filesystem::create_directories(options.writeTracksDir);
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
    std::printf("{");
    if (runFull) std::printf("\"full\": %s", scopeJson(full).c_str());
    if (runFull && runRoi) std::printf(", ");
    if (runRoi) std::printf("\"roi\": %s", scopeJson(roi).c_str());
    std::printf("}\n");
  } else {
    std::printf("%d trials (seeds %d-%d), %d frames each at %dx%d\n", options.trials, seed,
                seed + options.trials - 1, options.trial.frames, options.trial.width,
                options.trial.height);
    std::printf("%-16s %9s %8s %8s %8s %10s %9s %8s %8s %9s\n", "scope", "movements", "loss%",
                "class%", "real%", "frame-loss%", "spurious", "fps", "e2e fps", "move ms");
    if (runFull) printRow("full-image", full);
    if (runRoi) printRow("horopter-region", roi);
    if (runFull && runRoi)
      std::printf("region vs full image: real classification %s\n",
                  better ? "higher" : "NOT higher");
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
