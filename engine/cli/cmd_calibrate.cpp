// `horopter calibrate`: stereo calibration from chessboard views, written as
// an OpenCV FileStorage file that every other command takes with --calib.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <opencv2/imgcodecs.hpp>

#include "calibration/image_pairs.hpp"
#include "calibration_io.hpp"
#include "command_options.hpp"
#include "commands.hpp"
#include "horopter/core/error.hpp"
#include "horopter/vision/calibration.hpp"
#include "io/image_files.hpp"
#include "option_checks.hpp"

namespace horopter::cli {

namespace {

const char* kHelp =
    "Usage: horopter calibrate --left 'DIR/left*.jpg' --right 'DIR/right*.jpg'\n"
    "                          --board 9x6 --square 0.025 [-o calib.yml] [options]\n"
    "   or: horopter calibrate --convert IN --to horopter|ros [-o OUT] [--image-size WxH]\n\n"
    "Calibrates a stereo pair from views of a chessboard seen by both cameras: corners with\n"
    "sub-pixel refinement, intrinsics and distortion per camera, the extrinsics R, T, E and F,\n"
    "rectification (R1, R2, P1, P2, Q, valid ROIs) and the board plane's homography between\n"
    "the cameras per view. Prints the RMS reprojection error, the error per view and the mean\n"
    "epipolar error after rectification (|y_left - y_right| of the corners).\n\n";

const char* kHelpEnd =
    "\nViews where either image misses the board are named and left out; too few left -> error.\n";

constexpr CommandOption kOptions[] = {
    {.kind = OptionKind::Text,
     .flag = "--left",
     .value = "PATTERN",
     .help = "left images (a glob: quote it); a file name without wildcards is one image"},
    {.kind = OptionKind::Text,
     .flag = "--right",
     .value = "PATTERN",
     .help = "right images; paired with the left ones by the part the wildcards match"},
    {.kind = OptionKind::Text,
     .flag = "--board",
     .value = "WxH",
     .help = "inner corners per row x per column (OpenCV's sample board: 9x6)"},
    {.kind = OptionKind::Number,
     .flag = "--square",
     .value = "S",
     .min = 1e-9,
     .max = 1e9,
     .help = "side of one square, in the unit wanted for every length (0.025 = 25 mm in "
             "metres)"},
    {.kind = OptionKind::Integer,
     .flag = "--min-views",
     .value = "N",
     .min = 3,
     .max = 100000,
     .fallbackOf = [] { return defaultText(CalibrationOptions{}.minViews); },
     .help = "views with the board in both images needed"},
    {.kind = OptionKind::Number,
     .flag = "--alpha",
     .value = "A",
     .min = 0,
     .max = 1,
     .fallback = "0",
     .help = "rectification scaling: 0 = only valid pixels, 1 = all pixels"},
    {.kind = OptionKind::Text,
     .flag = "--out",
     .alias = "-o",
     .value = "FILE",
     .fallback = "calib.yml",
     .help = "the calibration file, .yml/.yaml or .xml; its folder is created if missing (with "
             "--convert --to ros: a folder, default ros)"},
    {.kind = OptionKind::Heading,
     .flag = "Calibrations from elsewhere and to ROS (formats: docs/calibration.md)"},
    {.kind = OptionKind::Text,
     .flag = "--ros-out",
     .value = "DIR",
     .help = "also write DIR/left.yaml and DIR/right.yaml, ROS camera_info files"},
    {.kind = OptionKind::Text,
     .flag = "--camera-name",
     .value = "N",
     .fallback = "stereo",
     .help = "camera_name in the ROS files: N/left, N/right"},
    {.kind = OptionKind::Text,
     .flag = "--convert",
     .value = "IN",
     .help = "instead of calibrating, read the calibration IN and write it with --to; IN: "
             "Horopter's file, an OpenCV file (K1, D1, K2, D2, R, T), the stereo_calib sample's "
             "intrinsics.yml (+ extrinsics.yml), a ROS camera_info left.yaml (+ right.yaml), or a "
             "folder holding a pair"},
    {.kind = OptionKind::Text,
     .flag = "--convert-right",
     .value = "F",
     .help = "the pair's second file where it is not named like the first (left -> right, "
             "intrinsics -> extrinsics)"},
    {.kind = OptionKind::Choice,
     .flag = "--to",
     .value = "FORMAT",
     .choices = "horopter,ros",
     .help = "with --convert: what to write"},
    kImageSizeOption,
};

cv::Mat readGrey(const std::string& path) {
  cv::Mat image = readImage(path, cv::IMREAD_GRAYSCALE);
  if (image.empty()) throw Error("cannot read image '" + path + "'");
  return image;
}

}  // namespace

int runCalibrate(Args& args) {
  if (args.flag("--help") || args.flag("-h")) {
    std::cout << kHelp << commandOptionsHelp(kOptions) << kHelpEnd;
    return 0;
  }
  // Every option is checked, and the images listed, before any is read.
  const CommandOptions o(args, kOptions);
  args.finish("calibrate");
  if (const auto in = o.optionalText("--convert")) return runCalibrationConversion(*in, o);
  for (const char* flag : {"--to", "--convert-right", "--image-size"})
    if (o.given(flag)) throw UsageError(std::string(flag) + " goes with --convert");
  const RosOutput rosOut = rosOutput(o);
  const auto left = o.optionalText("--left");
  const auto right = o.optionalText("--right");
  const auto board = o.optionalText("--board");
  const auto square = o.optionalNumber("--square");
  if (!left || !right)
    throw UsageError("--left and --right image patterns are required: see --help");
  if (!board) throw UsageError("--board WxH (inner corners, e.g. 9x6) is required");
  if (!square) throw UsageError("--square S (the side of one square, e.g. 0.025) is required");
  const BoardSpec spec{asUsageError([&] { return parseBoardSize(*board); }), *square};
  CalibrationOptions options;
  options.minViews = static_cast<int>(o.integer("--min-views"));
  options.alpha = o.number("--alpha");
  const std::string out = o.text("--out");
  requireWritableFile(out, "--out");
  const PairedFiles files = asUsageError([&] { return pairImageFiles(*left, *right); });

  for (const std::string& f : files.unpaired)
    std::cerr << "horopter: " << f << " has no partner image: left out\n";
  std::cerr << "horopter: " << files.pairs.size() << " pairs, board " << *board << ", square "
            << spec.squareSize << "\n";
  std::vector<StereoImagePair> pairs;
  for (const ImagePairFiles& p : files.pairs)
    pairs.push_back({p.name, readGrey(p.left), readGrey(p.right)});
  const BoardDetections detections = detectBoards(
      pairs, spec.innerCorners, [](const std::string& line) { std::cerr << line << "\n"; });
  pairs.clear();
  const StereoCalibration c = calibrateStereo(detections, spec, options);
  saveStereoCalibration(c, out);

  const RectifiedGeometry g = rectifiedGeometry(c);
  std::printf("views used: %zu of %zu\n", c.views.size(), c.views.size() + c.skipped.size());
  for (const std::string& s : c.skipped)
    std::printf("  skipped %s\n", s.c_str());
  std::printf("RMS reprojection error: %.4f px (stereo); per camera alone: left %.4f, right %.4f\n",
              c.rms, c.rmsLeft, c.rmsRight);
  std::printf("per-view RMS error (px):\n");
  double worst = 0;
  for (const ViewError& v : c.views) {
    std::printf("  %-28s left %.4f  right %.4f\n", v.name.c_str(), v.left, v.right);
    worst = std::max({worst, v.left, v.right});
  }
  std::printf("  worst view: %.4f px\n", worst);
  std::printf("epipolar error after rectification: %.4f px (mean |y_left - y_right| of corners)\n",
              c.epipolarError);
  std::printf("board-plane homography transfer error: %.4f px\n", c.homographyError);
  std::printf(
      "rectified: focal %.2f px, principal point (%.2f, %.2f), baseline %.5f (unit of "
      "--square)\n",
      g.focalPx, g.cx, g.cy, g.baseline);
  std::printf("wrote %s\n", out.c_str());
  if (rosOut.dir) writeRosPair(c, *rosOut.dir, rosOut.cameraName);
  return 0;
}

}  // namespace horopter::cli
