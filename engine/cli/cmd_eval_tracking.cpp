// `horopter eval-tracking`: tracker loss, detection false positives and
// frames/s on synthetic trials, with detection inside the horopter's region
// and over the full image.
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <utility>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "command_options.hpp"
#include "commands.hpp"
#include "eval/bootstrap.hpp"
#include "eval/parallel_trials.hpp"
#include "eval/seed_ranges.hpp"
#include "horopter/core/error.hpp"
#include "horopter/eval/tracking_eval.hpp"
#include "io/disparity_images.hpp"
#include "json_text.hpp"
#include "option_checks.hpp"
#include "report_format.hpp"
#include "run_annotation.hpp"
#include "shared_options.hpp"

namespace horopter::cli {

namespace {

const char* kEvalTrackingHelpStart =
    "Usage: horopter eval-tracking [--trials N] [--seed S] [--frames F] [--json] [options]\n\n"
    "Runs the whole pipeline (synthetic capture, closed loop with the head -> rectify ->\n"
    "disparity -> mask -> face and hand detection -> godfather election and tracking ->\n"
    "head control) on N synthetic trials, each twice: detection inside the horopter's region\n"
    "and over the full image. Trial i uses seed S + i: the main person's distance (1.0-1.7 m),\n"
    "lighting gain (0.7-1.3) and sensor noise (0-6 grey levels) come from it; every trial\n"
    "has skin-coloured clutter and a distractor outside the zone.\n\n"
    "Seeds (docs/evaluation.md): trials take seeds from the tuning range 0-499999 or the\n"
    "evaluation range 500000-999999, never both. --diagnose and --stills look\n"
    "inside the trials and are refused on evaluation seeds; a reported figure comes from a\n"
    "fresh block of at least 100 evaluation seeds, run once.\n\n"
    "Prints for each scope:\n"
    "  loss      tracker loss, with its 95 % confidence interval (bootstrap over trials): frames "
    "with a godfather by the truth (the main person inside\n"
    "            the zone for T s) where the head or a visible hand has no track, or one\n"
    "            further than max(20 px, half the face width)\n"
    "  head/left/right  the same per part (left, right: the person's own)\n"
    "  FP        detections (faces and hand candidates) that are not the head or a hand of\n"
    "            a person inside the zone, over all detections\n"
    "  detect    detection stage, ms per frame; vision: every stage but capture, ms per frame\n"
    "  fps       frames per second of the whole pipeline, rendering the scene included\n\n"
    "Options:\n";

constexpr CommandOption kOptions[] = {
    {.kind = OptionKind::Integer,
     .flag = "--trials",
     .value = "N",
     .min = 1,
     .max = 100000,
     .fallback = "20",
     .help = "number of trials"},
    kTrialJobsOption,
    {.kind = OptionKind::Integer,
     .flag = "--seed",
     .value = "S",
     .min = 0,
     .max = 9007199254740992.0,  // 2^53: seeds stay exact in JSON and Python
     .fallback = "1000",
     .help = "first trial's seed"},
    {.kind = OptionKind::Integer,
     .flag = "--frames",
     .value = "F",
     .min = 1,
     .max = 1000000,
     .fallback = "300",
     .help = "frames per trial (300: 10 s at 30 frames/s)"},
    {.kind = OptionKind::Text,
     .flag = "--size",
     .value = "WxH",
     .fallback = "640x480",
     .help = "image size, 64x64..4096x4096"},
    kTrialScopeOption,
    kTrialThreadsOption,
    kBackendOption,
    kHeadFormulaOption,
    {.kind = OptionKind::Switch,
     .flag = "--no-head-control",
     .help = "the head stays still (open loop)"},
    {.kind = OptionKind::Integer,
     .flag = "--num-disparities",
     .value = "N",
     .min = 16,
     .max = 1024,
     .fallback = "96",
     .help = "the front end's search range, a multiple of 16 (96: down to 0.7 m; nearer hands "
             "have no disparity, so no zone; a wider range also widens the band on the left "
             "the right view cannot match)"},
    {.kind = OptionKind::Integer,
     .flag = "--left-band",
     .value = "N",
     .min = 0,
     .max = 1024,
     .fallback = "0",
     .help = "match that band's columns over the disparities that fit there, where at least N "
             "do (0: off; the front end's --left-band)"},
    {.kind = OptionKind::Switch,
     .flag = "--frame-hands",
     .help = "head control pans to frame the head and tracked hands, not only the face (off "
             "by default: it measured worse)"},
    {.kind = OptionKind::Switch,
     .flag = "--no-follow-head-turns",
     .help = "the hand and head tracks stay where they were in the image when the head turns "
             "(by default they move with the image)"},
    {.kind = OptionKind::Switch,
     .flag = "--no-depth-face-sizes",
     .help = "in the region, search faces of every size instead of the sizes the zone's "
             "disparities allow (slower; for comparison)"},
    {.kind = OptionKind::Switch,
     .flag = "--require-region-better",
     .help = "exit with status 3 unless the region's tracker loss is below the full image's "
             "(for tests)"},
    {.kind = OptionKind::Text,
     .flag = "--stills",
     .value = "DIR",
     .help = "write every 10th frame of each run, annotated (run's view, with the truth's head "
             "and hands as white crosses) to DIR"},
    {.kind = OptionKind::Switch,
     .flag = "--diagnose",
     .help = "count, per part, why it was lost: the first of no-godfather, barely-visible, "
             "right-view-out, no-disparity, outside-mask, face-neck-cut, merged, no-skin, "
             "removed (no detection near the truth), filtered, no-track, swapped, elsewhere (a "
             "detection there, the track not); with -v, one line per lost part on stderr"},
    {.kind = OptionKind::Switch,
     .flag = "--json",
     .help = "print the results as one JSON object: per scope the figures, tracker_loss_ci95 "
             "(95 % bootstrap interval over trials, as a fraction), worst_trials and per_trial"},
    {.kind = OptionKind::Switch,
     .flag = "--verbose",
     .alias = "-v",
     .help = "one line per trial on stderr"},
    {.kind = OptionKind::Heading, .flag = "Detection, election, tracking and head control"},
};

struct TrackingTrial {
  TrialResult result;
  LossDiagnosis causes;
  long long fullSearches = 0;  // frames whose faces were searched over the whole region
};

eval::RatioEstimate lossInterval(const std::vector<TrackingTrial>& trials) {
  std::vector<double> lost, of;
  for (const TrackingTrial& t : trials) {
    lost.push_back(static_cast<double>(t.result.lostFrames));
    of.push_back(static_cast<double>(t.result.godfatherFrames));
  }
  return eval::bootstrapRatio(lost, of);
}

// Worst first: the highest loss, then the lowest seed.
std::vector<const TrialResult*> worstTrials(const std::vector<TrackingTrial>& trials, int count) {
  std::vector<const TrialResult*> order;
  for (const TrackingTrial& t : trials)
    order.push_back(&t.result);
  std::stable_sort(order.begin(), order.end(), [](const auto* a, const auto* b) {
    return a->trackerLoss() != b->trackerLoss() ? a->trackerLoss() > b->trackerLoss()
                                                : a->seed < b->seed;
  });
  order.resize(std::min<std::size_t>(order.size(), static_cast<std::size_t>(count)));
  return order;
}

using detail::Json;
using detail::jsonNumber;

Json trialJson(const TrialResult& r) {
  return Json{{"seed", r.seed},
              {"godfather_frames", r.godfatherFrames},
              {"lost_frames", r.lostFrames},
              {"tracker_loss", jsonNumber(r.trackerLoss())},
              {"head_lost", r.head.lost},
              {"left_hand_lost", r.leftHand.lost},
              {"right_hand_lost", r.rightHand.lost},
              {"detections", r.detections},
              {"false_detections", r.falseDetections}};
}

double lossRate(const PartScore& p) {
  return p.visible ? static_cast<double>(p.lost) / static_cast<double>(p.visible) : 0;
}

Json scoreJson(const ScopeScore& s, const std::vector<TrackingTrial>& trials) {
  const eval::RatioEstimate ci = lossInterval(trials);
  Json worst = Json::array();
  for (const TrialResult* r : worstTrials(trials, 5))
    worst.push_back(Json{{"seed", r->seed}, {"tracker_loss", jsonNumber(r->trackerLoss())}});
  Json perTrial = Json::array();
  for (const TrackingTrial& t : trials)
    perTrial.push_back(trialJson(t.result));
  return Json{{"scope", detectionScopeName(s.scope)},
              {"trials", s.trials},
              {"frames", s.frames},
              {"godfather_frames", s.godfatherFrames},
              {"lost_frames", s.lostFrames},
              {"tracker_loss", jsonNumber(s.trackerLoss())},
              {"head_loss", jsonNumber(lossRate(s.head))},
              {"left_hand_loss", jsonNumber(lossRate(s.leftHand))},
              {"right_hand_loss", jsonNumber(lossRate(s.rightHand))},
              {"detections", s.detections},
              {"false_detections", s.falseDetections},
              {"false_positive_rate", jsonNumber(s.falsePositiveRate())},
              {"detection_ms", jsonNumber(s.detectionMs)},
              {"tracking_ms", jsonNumber(s.trackingMs)},
              {"vision_ms", jsonNumber(s.visionMs)},
              {"fps", jsonNumber(s.fps())},
              {"tracker_loss_ci95", Json::array({jsonNumber(ci.low), jsonNumber(ci.high)})},
              {"worst_trials", std::move(worst)},
              {"per_trial", std::move(perTrial)}};
}

// The tuning options of the run, {name: value}, from their table.
template <class Params>
Json optionsJson(std::span<const NumberOption<Params>> table, const Params& p) {
  Json out = Json::object();
  for (const NumberOption<Params>& o : table)
    out[o.name] = o.integer() ? Json(static_cast<int>(o.get(p))) : jsonNumber(o.get(p));
  return out;
}

double pct(std::int64_t lost, std::int64_t of) {
  return of > 0 ? 100.0 * static_cast<double>(lost) / static_cast<double>(of) : 0;
}

}  // namespace

int runEvalTracking(Args& args) {
  if (args.flag("--help") || args.flag("-h")) {
    TrialOptions defaults;
    std::cout << kEvalTrackingHelpStart << commandOptionsHelp(kOptions)
              << optionFlagsHelp(detectorOptions(), defaults.detector)
              << optionFlagsHelp(electionOptions(), defaults.tracker.election)
              << optionFlagsHelp(trackerOptions(), defaults.tracker)
              << optionFlagsHelp(headControlOptions(), defaults.head)
              << optionFlagsHelp(zoneSearchOptions(), defaults.zoneSearch);
    return 0;
  }
  const CommandOptions opts(args, kOptions);
  TrialOptions base;
  base.detector = parseOptionFlags(args, detectorOptions(), base.detector);
  base.tracker.election = parseOptionFlags(args, electionOptions(), base.tracker.election);
  base.tracker = parseOptionFlags(args, trackerOptions(), base.tracker);
  base.head = parseOptionFlags(args, headControlOptions(), base.head);
  base.zoneSearch = parseOptionFlags(args, zoneSearchOptions(), base.zoneSearch);
  args.finish("eval-tracking");
  const int trials = static_cast<int>(opts.integer("--trials"));
  const int jobs = static_cast<int>(opts.integer("--jobs"));
  const long long seed = opts.integer("--seed");
  base.frames = static_cast<int>(opts.integer("--frames"));
  const ImageSize wh = parseImageSize(opts.text("--size"), "--size", {64, 64}, {4096, 4096});
  base.width = wh.width;
  base.height = wh.height;
  const std::string scope = opts.text("--scope");
  base.threads = static_cast<int>(opts.integer("--threads"));
  base.backend = opts.text("--backend");
  base.headControl = !opts.on("--no-head-control");
  const std::string formula = opts.text("--head-formula");
  base.head.formula = formula == "paper" ? PanTiltFormula::Paper : PanTiltFormula::Atan2;
  base.stereo.numDisparities = static_cast<int>(opts.integer("--num-disparities"));
  base.stereo.leftBand = static_cast<int>(opts.integer("--left-band"));
  if (opts.on("--frame-hands")) base.head.frameHands = true;
  if (opts.on("--no-follow-head-turns")) base.followHeadTurns = false;
  if (opts.on("--no-depth-face-sizes")) base.detector.depthFaceSizes = false;
  const bool requireBetter = opts.on("--require-region-better");
  const bool json = opts.on("--json");
  const bool verbose = opts.on("--verbose");
  const std::string stills = opts.text("--stills");
  const bool diagnose = opts.on("--diagnose");
  const eval::SeedUse seedUse = asUsageError(
      [&] { return eval::trialSeedUse(static_cast<std::uint64_t>(seed), trials, "--seed"); });
  if (diagnose) asUsageError([&] { eval::requireTuningSeeds(seedUse, "--diagnose"); });
  if (!stills.empty()) asUsageError([&] { eval::requireTuningSeeds(seedUse, "--stills"); });
  if (base.stereo.numDisparities % 16 != 0)
    throw UsageError("--num-disparities must be a positive multiple of 16");
  if (base.stereo.leftBand > base.stereo.numDisparities)
    throw UsageError("--left-band must be within 0..--num-disparities");
  if (requireBetter && scope != "both")
    throw UsageError("--require-region-better needs --scope both");
  requireBackend(base.backend);
  if (!stills.empty()) requireWritableFolder(stills, "--stills");

  std::vector<DetectionScope> scopes;
  if (scope != "full") scopes.push_back(DetectionScope::HoropterRegion);
  if (scope != "region") scopes.push_back(DetectionScope::FullImage);
  std::vector<ScopeScore> scores(scopes.size());
  std::vector<LossDiagnosis> causes(scopes.size());
  std::vector<std::vector<TrackingTrial>> perTrial(scopes.size());
  const bool tty = isatty(STDERR_FILENO) && !json;
  for (std::size_t k = 0; k < scopes.size(); ++k) {
    int finished = 0;
    const auto runOne = [&, k](int i) {
      TrialOptions o = base;
      o.seed = static_cast<std::uint64_t>(seed) + static_cast<std::uint64_t>(i);
      TrackingTrial trial;
      if (verbose) trial.causes.log = stderr;
      TrialFrameCallback dump;
      if (!stills.empty()) {
        dump = [&, scope = scopes[k], trialSeed = o.seed](const TrialFrame& t) {
          if (t.frame.index % 10 != 0) return;
          cv::Mat view = annotateFrame(t.frame, o.stereo, 0);
          for (const synth::PersonTruth& p : t.truth.people)
            for (cv::Point2f q : {p.head2d, p.leftHand2d, p.rightHand2d})
              cv::drawMarker(view, q, cv::Scalar(255, 255, 255), cv::MARKER_CROSS, 14, 2);
          cv::putText(view, t.lost ? "LOST" : (t.truthGodfather ? "ok" : "-"), cv::Point(8, 80),
                      cv::FONT_HERSHEY_SIMPLEX, 0.8, cv::Scalar(0, 0, 255), 2);
          const std::string path = stills + "/seed" + std::to_string(trialSeed) + "_" +
                                   (scope == DetectionScope::HoropterRegion ? "region" : "full") +
                                   "_" + std::to_string(t.frame.index) + ".png";
          writeImageFile(path, view, "still");
        };
      }
      TrialFrameCallback onFrame = [&](const TrialFrame& t) {
        if (dump) dump(t);
        if (diagnose) trial.causes.add(t, o);
        if (t.frame.detections && t.frame.detections->fullFaceSearch) ++trial.fullSearches;
      };
      trial.result = runTrackingTrial(o, scopes[k], {}, onFrame);
      trial.result.summary.trace.clear();
      return trial;
    };
    const auto done = [&, k](int, const TrackingTrial& t) {
      ++finished;
      const TrialResult& r = t.result;
      if (tty)
        std::fprintf(stderr, "\r%s: %d/%d trials done (seed %llu last)...        ",
                     detectionScopeName(scopes[k]), finished, trials,
                     static_cast<unsigned long long>(r.seed));
      if (verbose)
        std::fprintf(
            stderr,
            "%sseed %llu %-15s loss %5.1f%% (%lld/%lld)  FP %5.1f%%  detect %.2f ms  full face "
            "searches %lld/%lld\n",
            tty ? "\r" : "", static_cast<unsigned long long>(r.seed), detectionScopeName(scopes[k]),
            100 * r.trackerLoss(), static_cast<long long>(r.lostFrames),
            static_cast<long long>(r.godfatherFrames), 100 * r.falsePositiveRate(),
            r.stageMs("detection"), t.fullSearches, static_cast<long long>(r.frames));
    };
    perTrial[k] = eval::runTrials<TrackingTrial>(trials, jobs, runOne, done);
    for (const TrackingTrial& t : perTrial[k]) {
      scores[k].add(t.result);
      for (int part = 0; part < 3; ++part)
        for (int c = 0; c < static_cast<int>(LossCause::Count); ++c)
          causes[k].counts[part][c] += t.causes.counts[part][c];
    }
  }
  if (tty) std::fprintf(stderr, "\r%60s\r", "");

  const bool better = scores.size() == 2 && scores[0].trackerLoss() < scores[1].trackerLoss();
  if (json) {
    Json out{
        {"trials", trials},       {"seed", seed},        {"seed_use", eval::seedUseName(seedUse)},
        {"frames", base.frames},  {"width", base.width}, {"height", base.height},
        {"scopes", Json::array()}};
    for (std::size_t k = 0; k < scores.size(); ++k)
      out["scopes"].push_back(scoreJson(scores[k], perTrial[k]));
    if (scores.size() == 2) out["region_better"] = better;
    out["options"] = Json{{"detector", optionsJson(detectorOptions(), base.detector)},
                          {"election", optionsJson(electionOptions(), base.tracker.election)},
                          {"tracker", optionsJson(trackerOptions(), base.tracker)},
                          {"head_control", optionsJson(headControlOptions(), base.head)},
                          {"zone_search", optionsJson(zoneSearchOptions(), base.zoneSearch)}};
    writeJsonLine(detail::jsonText(out));
  } else {
    std::printf("%d trials (seeds %lld-%lld, %s), %d frames each at %dx%d, head control %s\n",
                trials, seed, seed + trials - 1, eval::seedUseName(seedUse), base.frames,
                base.width, base.height, base.headControl ? formula.c_str() : "off");
    std::printf("%-16s %9s %7s %6s %6s %6s %6s %6s %9s %9s %6s\n", "scope", "godfather", "loss%",
                "head%", "left%", "right%", "FP%", "dets", "detect ms", "vision ms", "fps");
    for (const ScopeScore& s : scores)
      std::printf("%-16s %9lld %7.2f %6.2f %6.2f %6.2f %6.1f %6lld %9.2f %9.2f %6.1f\n",
                  detectionScopeName(s.scope), static_cast<long long>(s.godfatherFrames),
                  100 * s.trackerLoss(), pct(s.head.lost, s.head.visible),
                  pct(s.leftHand.lost, s.leftHand.visible),
                  pct(s.rightHand.lost, s.rightHand.visible), 100 * s.falsePositiveRate(),
                  static_cast<long long>(s.detections), s.detectionMs, s.visionMs, s.fps());
    for (std::size_t k = 0; k < scores.size(); ++k) {
      eval::RatioEstimate ci = lossInterval(perTrial[k]);
      ci.value *= 100, ci.low *= 100, ci.high *= 100;
      std::printf("%s: loss %% [95%% CI] %s; worst trials (seed: loss):",
                  detectionScopeName(scores[k].scope), interval(ci).c_str());
      for (const TrialResult* r : worstTrials(perTrial[k], 5))
        std::printf("  %llu: %.1f%%", static_cast<unsigned long long>(r->seed),
                    100 * r->trackerLoss());
      std::printf("\n");
    }
    std::printf("%s\n", reportability(seedUse, trials).c_str());
    if (scores.size() == 2)
      std::printf("region vs full image: tracker loss %s, detection %.1fx faster\n",
                  better ? "lower" : "NOT lower",
                  scores[0].detectionMs > 0 ? scores[1].detectionMs / scores[0].detectionMs : 0.0);
  }
  if (diagnose) {
    std::FILE* out = json ? stderr : stdout;
    std::fprintf(out, "\nlost parts by cause (frames):\n%-16s %-6s", "scope", "part");
    for (int c = 0; c < static_cast<int>(LossCause::Count); ++c)
      std::fprintf(out, " %s", lossCauseName(static_cast<LossCause>(c)));
    std::fprintf(out, "\n");
    for (std::size_t k = 0; k < scopes.size(); ++k)
      for (int part = 0; part < 3; ++part) {
        std::fprintf(out, "%-16s %-6s", detectionScopeName(scopes[k]),
                     part == 0 ? "head" : (part == 1 ? "left" : "right"));
        for (int c = 0; c < static_cast<int>(LossCause::Count); ++c)
          std::fprintf(
              out, " %*lld",
              static_cast<int>(std::string(lossCauseName(static_cast<LossCause>(c))).size()),
              static_cast<long long>(causes[k].counts[part][c]));
        std::fprintf(out, "\n");
      }
  }
  if (requireBetter && !better) {
    std::fprintf(stderr,
                 "horopter eval-tracking: the region's tracker loss (%.2f%%) is not below the full "
                 "image's (%.2f%%)\n",
                 100 * scores[0].trackerLoss(), 100 * scores[1].trackerLoss());
    return 3;
  }
  return 0;
}

}  // namespace horopter::cli
