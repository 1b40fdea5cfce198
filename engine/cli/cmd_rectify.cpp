// `horopter rectify`: rectified pairs side by side with horizontal lines, to
// check a calibration by eye (matching features lie on one line).
#include <filesystem>
#include <iostream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "calibration/image_pairs.hpp"
#include "calibration_io.hpp"
#include "commands.hpp"
#include "horopter/core/error.hpp"
#include "horopter/vision/calibration.hpp"
#include "io/disparity_images.hpp"

namespace horopter::cli {

namespace {

const char* kHelp =
    "Usage: horopter rectify --calib PATH --left L --right R [-o DIR]\n\n"
    "Rectifies stereo pairs with a calibration from horopter calibrate (undistort-rectify maps\n"
    "computed once, then remapped per pair) and writes each pair side by side, left then\n"
    "right, with horizontal lines drawn across both every 32 rows and the valid regions (ROIs)\n"
    "outlined: after a good calibration a point lies on the same row in both halves.\n\n"
    "  --calib PATH     the calibration: Horopter's file, OpenCV's, ROS camera_info left.yaml\n"
    "                   (+ right.yaml) or a folder with a pair (docs/calibration.md)\n"
    "  --image-size WxH for a calibration without an image size (OpenCV's stereo_calib\n"
    "                   pair); default: the first left image's size\n"
    "  --left L         a left image, or a glob of them (quote it)\n"
    "  --right R        the right image(s), paired by the part the wildcards match\n"
    "  -o, --out DIR    output folder (default out/rectified); writes DIR/<left "
    "name>_rectified.png\n";

cv::Mat readColour(const std::string& path) {
  cv::Mat image = cv::imread(path, cv::IMREAD_COLOR);
  if (image.empty()) throw Error("cannot read image '" + path + "'");
  return image;
}

}  // namespace

int runRectify(Args& args) {
  if (args.flag("--help") || args.flag("-h")) {
    std::cout << kHelp;
    return 0;
  }
  const auto calibPath = args.value("--calib");
  const std::optional<ImageSize> imageSize = parseCalibrationImageSize(args);
  const auto left = args.value("--left");
  const auto right = args.value("--right");
  const std::string outDir = args.stringValue("-o", args.stringValue("--out", "out/rectified"));
  args.finish("rectify");
  if (!calibPath) throw Error("--calib FILE is required (write one with horopter calibrate)");
  if (!left || !right) throw Error("--left and --right images are required: see --help");

  requireCalibrationPath(*calibPath);  // before the images, which may be read for its size
  const PairedFiles files = pairImageFiles(*left, *right);
  for (const std::string& f : files.unpaired)
    std::cerr << "horopter: " << f << " has no partner image: left out\n";
  // A calibration without an image size takes the images' (checked against
  // the rectifier's size for every pair below).
  ImageSize size = imageSize.value_or(ImageSize{});
  if (!imageSize && !files.pairs.empty()) {
    const cv::Mat first = readColour(files.pairs.front().left);
    size = {first.cols, first.rows};
  }
  const StereoCalibration calibration = loadCalibrationArg(*calibPath, size);
  StereoRectifier stage(calibration);
  std::filesystem::create_directories(outDir);
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
