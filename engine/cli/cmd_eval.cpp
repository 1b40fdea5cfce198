// `horopter eval-stereo`: accuracy against ground truth, with cv::StereoBM
// measured beside Horopter in the same run.
#include <cstdio>
#include <iostream>
#include <optional>

#include "commands.hpp"
#include "horopter/core/error.hpp"
#include "horopter/eval/stereo_eval.hpp"
#include "io/disparity_images.hpp"
#include "json_text.hpp"
#include "report_format.hpp"

namespace horopter::cli {

namespace {

detail::Json json(const StereoScores& s) {
  using detail::jsonNumber;
  return detail::Json{{"bad1", jsonNumber(s.bad1, 4)},     {"bad2", jsonNumber(s.bad2, 4)},
                      {"avgerr", jsonNumber(s.avgerr, 4)}, {"density", jsonNumber(s.density, 4)},
                      {"ms", jsonNumber(s.ms, 3)},         {"backend", s.backend}};
}

void printRow(const char* who, const StereoScores& s) {
  std::printf("%-10s %-16s %8.2f %8.2f %8.3f %8.2f %10.2f\n", who, s.backend.c_str(), s.bad1,
              s.bad2, s.avgerr, s.density, s.ms);
}

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
           "the disparity.pfm that horopter disparity writes.\n\n"
        << stereoFlagsHelp(StereoParams{}, MedianParams{})
        << "Other:\n"
           "  --backend B              scalar, avx2, opencl, opencl:N or auto (default auto)\n"
           "  --peer opencv            also run cv::StereoBM with the same parameters and the\n"
           "                           same --threads\n"
           "  --runs N                 timed runs per method, after one warm-up (default 3)\n"
           "  --json                   print one JSON object {\"horopter\": {...}, \"opencv\": "
           "{...}}\n"
           "  --require-peer-parity    exit 1 if Horopter's bad-2.0 is worse than the peer's\n";
    return 0;
  }
  const std::string left = args.stringValue("--left", "");
  const std::string right = args.stringValue("--right", "");
  const std::string gt = args.stringValue("--gt", "");
  const std::optional<double> scaleGiven = args.optionalDouble("--gt-scale");
  const StereoParams stereo = parseStereoFlags(args, StereoParams{});
  const MedianParams median = parseMedianFlags(args, MedianParams{});
  const std::string backendName = args.stringValue("--backend", FrontendDefaults::backend);
  const std::string peer = args.stringValue("--peer", "");
  EvalOptions options;
  options.timedRuns = args.intValue("--runs", 3);
  options.threads = parseThreads(args);
  const bool asJson = args.flag("--json");
  const bool requireParity = args.flag("--require-peer-parity");
  args.finish("eval-stereo");

  if (left.empty() || right.empty() || gt.empty())
    throw Error("eval-stereo needs --left, --right and --gt: see horopter eval-stereo --help");
  // PFM ground truth is in px: its scale defaults to 1.
  const double scale = scaleGiven ? *scaleGiven : (isPfmFile(gt) ? 1.0 : 0.0);
  if (scale <= 0)
    throw Error("eval-stereo needs --gt-scale S > 0 (disparity = ground-truth value / S)");
  if (!peer.empty() && peer != "opencv")
    throw Error("unknown peer '" + peer + "': the only peer is opencv");
  if (requireParity && peer.empty()) throw Error("--require-peer-parity needs --peer opencv");
  if (options.timedRuns < 1 || options.timedRuns > 1000)
    throw Error("--runs must be within 1..1000");

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
  }
  if (requireParity && theirs && ours.bad2 > theirs->bad2) {
    std::fprintf(stderr, "horopter: bad-2.0 %.2f%% is worse than cv::StereoBM's %.2f%%\n",
                 ours.bad2, theirs->bad2);
    return 1;
  }
  return 0;
}

}  // namespace horopter::cli
