// `horopter rectify`: rectified pairs side by side with horizontal lines, to
// check a calibration by eye (matching features lie on one line).
#include <filesystem>
#include <iostream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "calibration/image_pairs.hpp"
#include "calibration_io.hpp"
#include "command_options.hpp"
#include "commands.hpp"
#include "horopter/core/error.hpp"
#include "horopter/vision/calibration.hpp"
#include "io/disparity_images.hpp"
#include "io/image_files.hpp"
#include "option_checks.hpp"

namespace horopter::cli {

namespace {

const char* kHelp =
    "Usage: horopter rectify --calib calib.yml --left L --right R [-o DIR]\n\n"
    "Rectifies stereo pairs with a calibration from horopter calibrate (undistort-rectify maps\n"
    "computed once, then remapped per pair) and writes each pair side by side, left then\n"
    "right, with horizontal lines drawn across both every 32 rows and the valid regions (ROIs)\n"
    "outlined: after a good calibration a point lies on the same row in both halves.\n\n"
    "Options:\n";

constexpr CommandOption kOptions[] = {
    {.kind = OptionKind::Text,
     .flag = "--calib",
     .value = "PATH",
     .help = "the calibration: Horopter's file, OpenCV's, ROS camera_info left.yaml (+ "
             "right.yaml) or a folder with a pair (docs/calibration.md)"},
    kImageSizeOption,
    {.kind = OptionKind::Text,
     .flag = "--left",
     .value = "L",
     .help = "a left image, or a glob of them (quote it)"},
    {.kind = OptionKind::Text,
     .flag = "--right",
     .value = "R",
     .help = "the right image(s), paired by the part the wildcards match"},
    {.kind = OptionKind::Text,
     .flag = "--out",
     .alias = "-o",
     .value = "DIR",
     .fallback = "out/rectified",
     .help = "output folder; writes DIR/<left name>_rectified.png"},
};

cv::Mat readColour(const std::string& path) {
  cv::Mat image = readImage(path, cv::IMREAD_COLOR);
  if (image.empty()) throw Error("cannot read image '" + path + "'");
  return image;
}

}  // namespace

int runRectify(Args& args) {
  if (args.flag("--help") || args.flag("-h")) {
    std::cout << kHelp << commandOptionsHelp(kOptions);
    return 0;
  }
  const CommandOptions o(args, kOptions);
  args.finish("rectify");
  const auto calibPath = o.optionalText("--calib");
  const auto left = o.optionalText("--left");
  const auto right = o.optionalText("--right");
  const std::string outDir = o.text("--out");
  if (!calibPath) throw UsageError("--calib FILE is required (write one with horopter calibrate)");
  if (!left || !right) throw UsageError("--left and --right images are required: see --help");
  const std::optional<ImageSize> imageSize = calibrationImageSize(o);
  asUsageError([&] { requireCalibrationPath(*calibPath); });  // before the images
  const PairedFiles files = asUsageError([&] { return pairImageFiles(*left, *right); });
  requireWritableFolder(outDir, "--out");
  for (const std::string& f : files.unpaired)
    std::cerr << "horopter: " << f << " has no partner image: left out\n";
  // A calibration without an image size takes the images' (checked against
  // the rectifier's size for every pair below).
  ImageSize size = imageSize.value_or(ImageSize{});
  if (!imageSize && !files.pairs.empty()) {
    const cv::Mat first = readColour(files.pairs.front().left);
    size = {first.cols, first.rows};
  }
  const StereoCalibration calibration =
      asUsageError([&] { return loadCalibrationArg(*calibPath, size); });
  StereoRectifier stage(calibration);
  for (const ImagePairFiles& p : files.pairs) {
    stage.rectify(readColour(p.left), readColour(p.right));
    cv::Mat sideBySide;
    cv::hconcat(stage.left(), stage.right(), sideBySide);
    const int w = stage.imageSize().width;
    cv::rectangle(sideBySide, calibration.roi1, cv::Scalar(255, 128, 0), 1);
    cv::rectangle(sideBySide, calibration.roi2 + cv::Point(w, 0), cv::Scalar(255, 128, 0), 1);
    for (int y = 16; y < sideBySide.rows; y += 32)
      cv::line(sideBySide, {0, y}, {sideBySide.cols - 1, y}, cv::Scalar(0, 255, 0), 1);
    const std::string stem = std::filesystem::path(p.left).stem().string();
    const std::string out = outDir + "/" + stem + "_rectified.png";
    writeImageFile(out, sideBySide, "rectified pair");
    std::cout << "wrote " << out << "  (" << p.name << ")\n";
  }
  return 0;
}

}  // namespace horopter::cli
