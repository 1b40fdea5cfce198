// `horopter eval-zone`: what zone-limited matching changes in the zone mask,
// against the full-range front end on the same frames and against the true
// zone, on the synthetic trials or on a real pair.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "command_options.hpp"
#include "commands.hpp"
#include "horopter/core/error.hpp"
#include "horopter/eval/stereo_eval.hpp"
#include "horopter/eval/zone_eval.hpp"
#include "horopter/vision/frontend.hpp"
#include "horopter/vision/geometry.hpp"
#include "horopter/vision/opencv.hpp"
#include "json_text.hpp"
#include "option_checks.hpp"
#include "report_format.hpp"
#include "shared_options.hpp"

namespace horopter::cli {

namespace {

const char* kHelp =
    "Usage: horopter eval-zone [--trials N --seed S --frames F | --left L --right R\n"
    "                          [--gt GT --gt-scale K]] [options]\n\n"
    "Runs the front end twice on each frame, over the full search range and zone-limited\n"
    "(each frame searches only from a little below its smallest horopter threshold up to\n"
    "the largest disparity wanted: `run --zone-search 1`), and prints how far the zone\n"
    "mask moves: the zone-limited mask's precision and recall against the full-range\n"
    "mask, and both masks' against the true zone where it is known, with the mean number\n"
    "of disparities searched (the bench rows frontend/*/scene and /zone measure speed).\n"
    "With the guard below the range on (--zone-guard-step N, default 1; 0: off) the\n"
    "zone-limited front end also checks every Nth disparity below its range; the command\n"
    "then also runs the range without the guard and prints both masks, and how many\n"
    "disparities the guard checked.\n\n"
    "Synthetic (default): eval-tracking's closed-loop trials S .. S+N-1 (default 10240, 4\n"
    "  trials of 300 frames; the head verges on the person); the truth is the scene's.\n"
    "Real pair: a rectified pair; the zone's fixation is --fixation-disparity px on the\n"
    "  centre column (default: the median valid disparity of the full-range map, so that\n"
    "  about half the scene lies inside) and --focal-px (default: the image width). With\n"
    "  --gt (disparity = value / K, 0 = unknown), the true zone is the ground truth's.\n\n";

constexpr CommandOption kOptions[] = {
    {.kind = OptionKind::Heading, .flag = "Synthetic trials"},
    {.kind = OptionKind::Integer,
     .flag = "--trials",
     .value = "N",
     .min = 1,
     .max = 100000,
     .fallback = "4",
     .help = "trials"},
    {.kind = OptionKind::Integer,
     .flag = "--seed",
     .value = "S",
     .min = 0,
     .max = 9007199254740992.0,  // 2^53: seeds stay exact in JSON and Python
     .fallback = "10240",
     .help = "first trial's seed"},
    {.kind = OptionKind::Integer,
     .flag = "--frames",
     .value = "F",
     .min = 1,
     .max = 100000,
     .fallback = "300",
     .help = "frames per trial"},
    {.kind = OptionKind::Heading, .flag = "Real pair"},
    {.kind = OptionKind::Text, .flag = "--left", .value = "L", .help = "the left image"},
    {.kind = OptionKind::Text, .flag = "--right", .value = "R", .help = "the right image"},
    {.kind = OptionKind::Text,
     .flag = "--gt",
     .value = "GT",
     .help = "ground truth (8/16-bit image or PFM) for the true zone"},
    {.kind = OptionKind::Number,
     .flag = "--gt-scale",
     .value = "K",
     .min = 1e-9,
     .max = 1e9,
     .help = "disparity = ground-truth value / K (needed with --gt)"},
    kFixationDisparityOption,
    kFocalPxOption,
    {.kind = OptionKind::Heading, .flag = "Other"},
    kBackendOption,
    {.kind = OptionKind::Switch, .flag = "--json", .help = "print one JSON object"},
};

void printAgreement(const char* what, const MaskAgreement& a) {
  std::printf("%-34s %9.3f %% %9.3f %%   (%lld in both, %lld test only, %lld reference only)\n",
              what, 100 * a.precision(), 100 * a.recall(), static_cast<long long>(a.truePositive),
              static_cast<long long>(a.falsePositive), static_cast<long long>(a.falseNegative));
}

detail::Json agreementJson(const MaskAgreement& a) {
  using detail::jsonNumber;
  return detail::Json{{"precision", jsonNumber(a.precision(), 6)},
                      {"recall", jsonNumber(a.recall(), 6)},
                      {"true_positive", a.truePositive},
                      {"false_positive", a.falsePositive},
                      {"false_negative", a.falseNegative}};
}

// The median valid disparity of the full-range map, px.
double medianDisparityPx(const StereoParams& stereo, const MedianParams& median,
                         const Backend& backend, const cv::Mat& l, const cv::Mat& r) {
  StereoFrontend frontend(stereo, median, backend);
  const Image& d = frontend.computeDisparity(viewOf(l), viewOf(r));
  std::vector<int> valid;
  for (int y = 0; y < d.height(); ++y)
    for (int x = 0; x < d.width(); ++x) {
      const int v = d.row<std::int16_t>(y)[x];
      if (v != invalidDisparity(stereo) && v > 0) valid.push_back(v);
    }
  if (valid.empty()) throw Error("the full-range map has no positive disparity to fixate on");
  std::nth_element(valid.begin(), valid.begin() + valid.size() / 2, valid.end());
  return valid[valid.size() / 2] / static_cast<double>(kDisparityScale);
}

}  // namespace

int runEvalZone(Args& args) {
  if (args.flag("--help") || args.flag("-h")) {
    std::cout << kHelp << commandOptionsHelp(kOptions) << "Zone search:\n"
              << optionFlagsHelp(zoneSearchOptions(), ZoneSearch{})
              << stereoFlagsHelp(StereoParams{}, MedianParams{}, "1");
    return 0;
  }
  const CommandOptions o(args, kOptions);
  const StereoParams stereo = parseStereoFlags(args, StereoParams{});
  const MedianParams median = parseMedianFlags(args, MedianParams{});
  ZoneSearch zone = parseOptionFlags(args, zoneSearchOptions(), ZoneSearch{});
  zone.enabled = 1;  // what this command measures
  // Each front end's pool: one thread unless --threads says otherwise.
  const int threads = parseThreads(args, 1);
  args.finish("eval-zone");
  const int trials = static_cast<int>(o.integer("--trials"));
  const long long seed = o.integer("--seed");
  const int frames = static_cast<int>(o.integer("--frames"));
  const std::string left = o.text("--left");
  const std::string right = o.text("--right");
  const std::string gt = o.text("--gt");
  const double gtScale = o.optionalNumber("--gt-scale").value_or(0);
  const std::optional<double> fixationPx = o.optionalNumber("--fixation-disparity");
  const std::optional<double> focalPx = o.optionalNumber("--focal-px");
  const std::string backendName = o.text("--backend");
  const bool json = o.on("--json");
  asUsageError([&] { validate(zone, stereo); });
  if (left.empty() != right.empty()) throw UsageError("a real pair needs both --left and --right");
  if (!gt.empty() && !(gtScale > 0))
    throw UsageError("--gt needs --gt-scale K > 0 (disparity = ground-truth value / K)");
  if (!left.empty()) {
    requireFile(left, "left image");
    requireFile(right, "right image");
  }
  if (!gt.empty()) requireFile(gt, "ground truth");
  requireBackend(backendName);
  const Backend& backend = findBackend(backendName);

  ZoneEvalResult result;
  std::string what;
  if (left.empty()) {
    result = evaluateZoneOnSyntheticTrials(static_cast<std::uint64_t>(seed), trials, frames, stereo,
                                           median, zone, backend, threads);
    what = "synthetic trials " + std::to_string(seed) + ".." + std::to_string(seed + trials - 1) +
           ", " + std::to_string(frames) + " frames each";
  } else {
    const cv::Mat l = loadGrey(left, "left image"), r = loadGrey(right, "right image");
    if (l.size() != r.size()) throw Error("the left and right images differ in size");
    const double fixation = fixationPx.value_or(medianDisparityPx(stereo, median, backend, l, r));
    RectifiedGeometry g;
    g.focalPx = focalPx.value_or(l.cols);
    g.cx = (l.cols - 1) / 2.0;
    g.cy = (l.rows - 1) / 2.0;
    g.baseline = 1.0;
    const std::vector<std::int16_t> thresholds =
        horopterThresholds(g, l.cols, fixationFromDisparity(g, g.cx, fixation));
    cv::Mat inside, known;
    if (!gt.empty()) {
      const cv::Mat gtPx = loadGroundTruth(gt, gtScale);
      if (gtPx.size() != l.size()) throw Error("the ground truth's size differs from the pair's");
      inside = cv::Mat::zeros(l.size(), CV_8UC1);
      known = gtPx > 0;
      for (int y = 0; y < l.rows; ++y)
        for (int x = 0; x < l.cols; ++x)
          if (std::lround(gtPx.at<float>(y, x) * kDisparityScale) >= thresholds[x])
            inside.at<std::uint8_t>(y, x) = 255;
    }
    ZoneEvaluator evaluator(stereo, median, zone, backend, threads);
    evaluator.addFrame(l, r, thresholds, inside, known, result);
    char fix[64];
    std::snprintf(fix, sizeof fix, ", fixation %.2f px", fixation);
    what = left + fix;
  }

  const double searched = result.searchedDisparities / std::max(1, result.frames);
  const double checked = result.checkedDisparities / std::max(1, result.frames);
  if (json) {
    detail::Json out{{"input", what},
                     {"frames", result.frames},
                     {"full_disparities", stereo.numDisparities},
                     {"mean_searched_disparities", detail::jsonNumber(searched, 3)},
                     {"zone_guard_step", zone.guardStep},
                     {"zone_vs_full", agreementJson(result.zoneVsFull)}};
    if (result.hasGuard) {
      out["mean_guard_checked_disparities"] = detail::jsonNumber(checked, 3);
      out["unguarded_vs_full"] = agreementJson(result.unguardedVsFull);
      if (result.hasTruth) out["unguarded_vs_truth"] = agreementJson(result.unguardedVsTruth);
    }
    if (result.hasTruth) {
      out["full_vs_truth"] = agreementJson(result.fullVsTruth);
      out["zone_vs_truth"] = agreementJson(result.zoneVsTruth);
    }
    writeJsonLine(detail::jsonText(out));
    return 0;
  }
  // No times here: the bench rows frontend/*/scene and /zone measure speed.
  std::printf("%s\n%d frame(s); disparities searched: %.1f of %d on average (backend %s)\n",
              what.c_str(), result.frames, searched, stereo.numDisparities, backend.name.c_str());
  if (result.hasGuard)
    std::printf("guard below the range: every %d px, %.1f disparities checked on average\n",
                zone.guardStep, checked);
  else
    std::printf("guard below the range: off (--zone-guard-step 0)\n");
  std::printf("\n%-34s %11s %11s\n", "zone mask", "precision", "recall");
  if (result.hasGuard) printAgreement("zone-limited, no guard vs full", result.unguardedVsFull);
  printAgreement(result.hasGuard ? "zone-limited + guard vs full" : "zone-limited vs full range",
                 result.zoneVsFull);
  if (result.hasTruth) {
    printAgreement("full range vs true zone", result.fullVsTruth);
    if (result.hasGuard) printAgreement("zone-limited, no guard vs true", result.unguardedVsTruth);
    printAgreement(result.hasGuard ? "zone-limited + guard vs true" : "zone-limited vs true zone",
                   result.zoneVsTruth);
  }
  return 0;
}

}  // namespace horopter::cli
