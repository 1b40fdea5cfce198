// `horopter calibrate`: stereo calibration from chessboard views, written as
// an OpenCV FileStorage file that every other command takes with --calib.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <opencv2/imgcodecs.hpp>

#include "calibration/image_pairs.hpp"
#include "calibration_io.hpp"
#include "commands.hpp"
#include "horopter/core/error.hpp"
#include "horopter/vision/calibration.hpp"

namespace horopter::cli {

namespace {

const char* kHelp =
    "Usage: horopter calibrate --left 'DIR/left*.jpg' --right 'DIR/right*.jpg'\n"
    "                          --board 9x6 --square 0.025 [-o calib.yml] [options]\n\n"
    "Calibrates a stereo pair from views of a chessboard seen by both cameras: corners with\n"
    "sub-pixel refinement, intrinsics and distortion per camera, the extrinsics R, T, E and F,\n"
    "rectification (R1, R2, P1, P2, Q, valid ROIs) and the board plane's homography between\n"
    "the cameras per view. Prints the RMS reprojection error, the error per view and the mean\n"
    "epipolar error after rectification (|y_left - y_right| of the corners).\n\n"
    "  --left PATTERN    left images (a glob: quote it); a file name without wildcards is one "
    "image\n"
    "  --right PATTERN   right images; paired with the left ones by the part the wildcards match\n"
    "  --board WxH       inner corners per row x per column (OpenCV's sample board: 9x6)\n"
    "  --square S        side of one square, in the unit wanted for every length (0.025 = 25 mm\n"
    "                    in metres)\n"
    "  --min-views N     views with the board in both images needed (default 5, at least 3)\n"
    "  --alpha A         rectification scaling: 0 = only valid pixels (default), 1 = all pixels\n"
    "  -o, --out FILE    the calibration file, .yml/.yaml or .xml (default calib.yml); its folder\n"
    "                    is created if missing\n\n"
    "Views where either image misses the board are named and left out; too few left -> error.\n";

cv::Mat readGrey(const std::string& path) {
  cv::Mat image = cv::imread(path, cv::IMREAD_GRAYSCALE);
  if (image.empty()) throw Error("cannot read image '" + path + "'");
  return image;
}

}  // namespace

int runCalibrate(Args& args) {
  if (args.flag("--help") || args.flag("-h")) {
    std::cout << kHelp << kCalibrationConversionHelp;
    return 0;
  }
  if (const auto in = args.value("--convert")) return runCalibrationConversion(*in, args);
  const RosOutput rosOut = parseRosOutput(args);
  const auto left = args.value("--left");
  const auto right = args.value("--right");
  const auto board = args.value("--board");
  const auto square = args.optionalDouble("--square");
  CalibrationOptions options;
  options.minViews = args.intValue("--min-views", options.minViews);
  options.alpha = args.doubleValue("--alpha", options.alpha);
  const std::string out = args.stringValue("-o", args.stringValue("--out", "calib.yml"));
  args.finish("calibrate");
  if (!left || !right) throw Error("--left and --right image patterns are required: see --help");
  if (!board) throw Error("--board WxH (inner corners, e.g. 9x6) is required");
  if (!square) throw Error("--square S (the side of one square, e.g. 0.025) is required");
  const BoardSpec spec{parseBoardSize(*board), *square};
  if (!std::isfinite(spec.squareSize) || !(spec.squareSize > 0))
    throw Error("--square must be a positive length, got " + std::to_string(*square));

  const PairedFiles files = pairImageFiles(*left, *right);
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
  const std::filesystem::path parent = std::filesystem::path(out).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
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
