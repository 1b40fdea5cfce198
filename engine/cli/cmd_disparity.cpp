// `horopter disparity` and `horopter run`: the front end on one stereo pair,
// written to image files.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>

#include "command_options.hpp"
#include "commands.hpp"
#include "default_input.hpp"
#include "horopter/core/error.hpp"
#include "horopter/eval/stereo_eval.hpp"
#include "horopter/vision/frontend.hpp"
#include "horopter/vision/geometry.hpp"
#include "horopter/vision/opencv.hpp"
#include "io/disparity_images.hpp"
#include "option_checks.hpp"
#include "shared_options.hpp"

namespace horopter::cli {

namespace {

struct PairJob {
  std::string left, right, outDir;
  StereoParams stereo;
  MedianParams median;
  std::string backend = FrontendDefaults::backend;
  int threads = 1;
  std::optional<double> fixationDisparity;  // px; default: the middle of the search range
  std::optional<double> focalPx;            // px; default: the image width
};

int runPair(const PairJob& job) {
  const cv::Mat leftColour = loadColour(job.left, "left image");
  const cv::Mat rightColour = loadColour(job.right, "right image");
  if (leftColour.size() != rightColour.size())
    throw Error("left image is " + std::to_string(leftColour.cols) + "x" +
                std::to_string(leftColour.rows) + " but right image is " +
                std::to_string(rightColour.cols) + "x" + std::to_string(rightColour.rows) +
                ": a rectified pair has one size");
  const cv::Mat left = toGrey(leftColour);
  const cv::Mat right = toGrey(rightColour);

  const Backend& backend = findBackend(job.backend);
  StereoFrontend frontend(job.stereo, job.median, backend, job.threads);
  std::cerr << "horopter: " << left.cols << "x" << left.rows << ", disparities "
            << job.stereo.minDisparity << ".."
            << job.stereo.minDisparity + job.stereo.numDisparities - 1 << ", block "
            << job.stereo.blockSize << ", backend " << backend.name << ", " << job.threads
            << " thread(s)\n";
  frontend.computeDisparity(viewOf(left), viewOf(right));

  RectifiedGeometry geometry;
  geometry.focalPx = job.focalPx.value_or(left.cols);
  geometry.cx = (left.cols - 1) / 2.0;
  geometry.baseline = 1.0;  // thresholds in pixels do not depend on the unit
  const double fixation =
      job.fixationDisparity.value_or(job.stereo.minDisparity + job.stereo.numDisparities / 2.0);
  if (!job.fixationDisparity && fixation <= 0)
    throw Error("the middle of the search range (" + std::to_string(fixation) +
                " px) is not in front of the cameras: pass --fixation-disparity D with D > 0");
  const auto thresholds = horopterThresholds(
      geometry, left.cols, fixationFromDisparity(geometry, geometry.cx, fixation));
  frontend.computeMask(thresholds, viewOf(leftColour));
  writeFrontendOutputs(job.outDir, frontend);

  const auto& t = frontend.timings();
  const cv::Mat mask = matOf(frontend.mask());
  const double inside = 100.0 * cv::countNonZero(mask) / static_cast<double>(mask.total());
  std::printf(
      "front end %.1f ms (prefilter %.1f, match %.1f, cleanup %.1f, median %.1f, mask %.1f)\n"
      "horopter: fixation disparity %.1f px at the centre column; %.1f%% of pixels inside\n"
      "wrote %s/{disparity.png, disparity16.png, disparity.pfm, disparity_color.png, mask.png, "
      "segmented.png}\n",
      t.total(), t.prefilter, t.match, t.cleanup, t.median, t.mask, fixation, inside,
      job.outDir.c_str());
  return 0;
}

constexpr CommandOption kOptions[] = {
    {.kind = OptionKind::Heading, .flag = "Input"},
    {.kind = OptionKind::Switch,
     .flag = "--example",
     .help = "Middlebury's Aloe pair from Debian's opencv-doc instead of LEFT RIGHT"},
    {.kind = OptionKind::Heading, .flag = "Horopter zone"},
    kFixationDisparityOption,
    kFocalPxOption,
    {.kind = OptionKind::Heading, .flag = "Other"},
    kBackendOption,
    {.kind = OptionKind::Text,
     .flag = "--out",
     .alias = "-o",
     .value = "DIR",
     .fallback = "out",
     .help = "output folder"},
};

const char* kPairHelpTail =
    "Writes DIR/disparity.png (16-bit, 1/16 px, 0 = invalid or <= 0), DIR/disparity16.png\n"
    "(16-bit, 1/16 px + 32768, 0 = invalid: keeps negative disparities),\n"
    "DIR/disparity.pfm (Middlebury PFM, float px, inf = invalid), DIR/disparity_color.png\n"
    "(near = red, far = blue, invalid = black; a colour scale in px in the bottom-right\n"
    "corner), DIR/mask.png (255 = inside the zone) and\n"
    "DIR/segmented.png (the left image, zeroed outside the zone).\n";

}  // namespace

int runDisparity(Args& args) {
  if (args.flag("--help") || args.flag("-h")) {
    std::cout << "Usage: horopter disparity LEFT RIGHT [-o DIR] [options]\n"
                 "       horopter disparity --example [-o DIR] [options]\n\n"
                 "Runs the front end (x-Sobel prefilter, SAD matching, left-right check,\n"
                 "speckle filter, hole-filling median, horopter mask) on a rectified pair.\n"
                 "--example takes Middlebury's Aloe pair from Debian's opencv-doc (1282x1110,\n"
                 "disparities 43..211) with 224 disparities unless --num-disparities is given.\n\n"
              << stereoFlagsHelp(StereoParams{}, MedianParams{}) << commandOptionsHelp(kOptions)
              << kPairHelpTail;
    return 0;
  }
  const CommandOptions o(args, kOptions);
  PairJob job;
  const bool example = o.on("--example");
  if (example) job.stereo.numDisparities = 224;  // Aloe's disparities reach 211 px
  job.stereo = parseStereoFlags(args, job.stereo);
  job.median = parseMedianFlags(args, job.median);
  job.threads = parseThreads(args);
  job.backend = o.text("--backend");
  job.fixationDisparity = o.optionalNumber("--fixation-disparity");
  job.focalPx = o.optionalNumber("--focal-px");
  job.outDir = o.text("--out");
  const auto files = args.positionals();
  args.finish("disparity");
  if (example) {
    if (!files.empty()) throw UsageError("--example takes no image paths: drop them or --example");
    const StereoPairFiles pair = asUsageError([] { return defaultStereoPair(); });
    std::cerr << "horopter: default input " << pair.left << " + " << pair.right << "\n";
    job.left = pair.left;
    job.right = pair.right;
  } else {
    if (files.size() != 2)
      throw UsageError("horopter disparity needs LEFT and RIGHT image paths, got " +
                       std::to_string(files.size()) + " path(s): see horopter disparity --help");
    job.left = files[0];
    job.right = files[1];
  }
  requireFile(job.left, "left image");
  requireFile(job.right, "right image");
  requireBackend(job.backend);
  requireWritableFolder(job.outDir, "--out");
  return runPair(job);
}

}  // namespace horopter::cli
