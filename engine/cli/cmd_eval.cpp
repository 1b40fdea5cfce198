// `horopter eval-stereo`: accuracy against ground truth, with cv::StereoBM
// measured beside Horopter in the same run.
#include <cstdio>
#include <iostream>
#include <optional>

#include "command_options.hpp"
#include "commands.hpp"
#include "horopter/core/error.hpp"
#include "horopter/eval/stereo_eval.hpp"
#include "io/disparity_images.hpp"
#include "json_text.hpp"
#include "option_checks.hpp"
#include "report_format.hpp"
#include "shared_options.hpp"

namespace horopter::cli {

namespace {

detail::Json json(const StereoScores& s) {
  using detail::jsonNumber;
  detail::Json out{{"bad1", jsonNumber(s.bad1, 4)},     {"bad2", jsonNumber(s.bad2, 4)},
                   {"avgerr", jsonNumber(s.avgerr, 4)}, {"density", jsonNumber(s.density, 4)},
                   {"ms", jsonNumber(s.ms, 3)},         {"backend", s.backend}};
  if (s.leftBand)
    out["left_band"] =
        detail::Json{{"reachable", s.leftBand->reachable},
                     {"unreachable", s.leftBand->unreachable},
                     {"reachable_bad2", jsonNumber(s.leftBand->reachableBad2, 4)},
                     {"reachable_density", jsonNumber(s.leftBand->reachableDensity, 4)},
                     {"false_matches", jsonNumber(s.leftBand->falseMatches, 4)}};
  return out;
}

void printRow(const char* who, const StereoScores& s) {
  std::printf("%-10s %-16s %8.2f %8.2f %8.3f %8.2f %10.2f\n", who, s.backend.c_str(), s.bad1,
              s.bad2, s.avgerr, s.density, s.ms);
}

constexpr CommandOption kOptions[] = {
    {.kind = OptionKind::Heading, .flag = "Input"},
    {.kind = OptionKind::Text, .flag = "--left", .value = "L", .help = "the left image"},
    {.kind = OptionKind::Text, .flag = "--right", .value = "R", .help = "the right image"},
    {.kind = OptionKind::Text,
     .flag = "--gt",
     .value = "GT",
     .help = "the ground truth: an 8- or 16-bit image, or a PFM file"},
    {.kind = OptionKind::Number,
     .flag = "--gt-scale",
     .value = "S",
     .min = 1e-9,
     .max = 1e9,
     .help = "disparity = ground-truth value / S (required for images; PFM: default 1)"},
    {.kind = OptionKind::Heading, .flag = "Other"},
    kBackendOption,
    {.kind = OptionKind::Choice,
     .flag = "--peer",
     .value = "P",
     .choices = "opencv",
     .help = "also run cv::StereoBM with the same parameters and the same --threads"},
    {.kind = OptionKind::Integer,
     .flag = "--runs",
     .value = "N",
     .min = 1,
     .max = 1000,
     .fallback = "3",
     .help = "timed runs per method, after one warm-up"},
    {.kind = OptionKind::Switch,
     .flag = "--json",
     .help = "print one JSON object {\"horopter\": {...}, \"opencv\": {...}}"},
    {.kind = OptionKind::Switch,
     .flag = "--require-peer-parity",
     .help = "exit 1 if Horopter's bad-2.0 is worse than the peer's"},
};

}  // namespace

int runEvalStereo(Args& args) {
  if (args.flag("--help") || args.flag("-h")) {
    std::cout
        << "Usage: horopter eval-stereo --left L --right R --gt GT --gt-scale S [options]\n\n"
           "Scores Horopter's disparity (the front end through the median) against ground\n"
           "truth: bad-1.0 and bad-2.0 (% of pixels with ground truth whose error exceeds 1 or\n"
           "2 px; invalid outputs count as bad), avgerr (mean |error| in px over valid outputs),\n"
           "density (% of pixels with ground truth that have a valid output) and ms per frame.\n"
           "Ground truth: 8- or 16-bit image, disparity = value / S, 0 = unknown; or\n"
           "Middlebury's PFM (float px, inf = unknown; --gt-scale defaults to 1), such as\n"
           "the disparity.pfm that horopter disparity writes. With --left-band N, the band's\n"
           "pixels are scored apart too: those whose true match the band's search reaches,\n"
           "and the share of those it cannot reach that were given a (false) match.\n\n"
        << stereoFlagsHelp(StereoParams{}, MedianParams{}) << commandOptionsHelp(kOptions);
    return 0;
  }
  const CommandOptions o(args, kOptions);
  const StereoParams stereo = parseStereoFlags(args, StereoParams{});
  const MedianParams median = parseMedianFlags(args, MedianParams{});
  EvalOptions options;
  options.threads = parseThreads(args);
  args.finish("eval-stereo");
  const std::string left = o.text("--left");
  const std::string right = o.text("--right");
  const std::string gt = o.text("--gt");
  const std::string backendName = o.text("--backend");
  const std::string peer = o.text("--peer");
  options.timedRuns = static_cast<int>(o.integer("--runs"));
  const bool asJson = o.on("--json");
  const bool requireParity = o.on("--require-peer-parity");
  if (left.empty() || right.empty() || gt.empty())
    throw UsageError("eval-stereo needs --left, --right and --gt: see horopter eval-stereo --help");
  if (requireParity && peer.empty()) throw UsageError("--require-peer-parity needs --peer opencv");
  requireFile(left, "left image");
  requireFile(right, "right image");
  requireFile(gt, "ground truth");
  // PFM ground truth is in px: its scale defaults to 1.
  const double scale = o.optionalNumber("--gt-scale").value_or(isPfmFile(gt) ? 1.0 : 0.0);
  if (scale <= 0)
    throw UsageError("eval-stereo needs --gt-scale S > 0 (disparity = ground-truth value / S)");
  requireBackend(backendName);

  const cv::Mat l = loadGrey(left, "left image");
  const cv::Mat r = loadGrey(right, "right image");
  const cv::Mat g = loadGroundTruth(gt, scale);
  const Backend& backend = findBackend(backendName);
  const StereoScores ours = evaluateHoropter(l, r, g, stereo, median, backend, options);
  std::optional<StereoScores> theirs;
  if (!peer.empty()) {
    if (stereo.preFilterType == PreFilterType::None)
      std::cerr << "horopter: note: cv::StereoBM has no unfiltered mode; the peer runs with its "
                   "normalized-response prefilter\n";
    theirs = evaluateOpenCvStereoBM(l, r, g, stereo, options);
  }

  if (asJson) {
    detail::Json out{{"horopter", json(ours)}};
    if (theirs) out["opencv"] = json(*theirs);
    writeJsonLine(detail::jsonText(out));
  } else {
    std::printf("%-10s %-16s %8s %8s %8s %8s %10s\n", "", "backend", "bad1%", "bad2%", "avgerr",
                "density%", "ms/frame");
    printRow("horopter", ours);
    if (theirs) printRow("opencv", *theirs);
    if (const auto& b = ours.leftBand)
      std::printf(
          "left band: %ld pixels with ground truth its search reaches: bad2 %.2f%%, density "
          "%.2f%%; %ld it cannot reach: %.2f%% given a (false) match\n",
          b->reachable, b->reachableBad2, b->reachableDensity, b->unreachable, b->falseMatches);
  }
  if (requireParity && theirs && ours.bad2 > theirs->bad2) {
    std::fprintf(stderr, "horopter: bad-2.0 %.2f%% is worse than cv::StereoBM's %.2f%%\n",
                 ours.bad2, theirs->bad2);
    return 1;
  }
  return 0;
}

}  // namespace horopter::cli
