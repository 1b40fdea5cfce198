// Calibrations in and out on the command line: the --calib path every
// command takes (any format loadStereoCalibration reads), `horopter calibrate
// --convert` and `--ros-out`. See docs/calibration.md.
#pragma once

#include <optional>
#include <string>

#include "args.hpp"
#include "command_options.hpp"
#include "horopter/vision/calibration.hpp"

namespace horopter::cli {

// --image-size WxH, the image size for a calibration that gives none (the
// stereo_calib sample's pair): the entry of the commands' tables, and its
// value (nullopt when absent).
inline constexpr CommandOption kImageSizeOption = {
    .kind = OptionKind::Text,
    .flag = "--image-size",
    .value = "WxH",
    .help = "the image size, for a calibration that gives none (OpenCV's stereo_calib pair)"};
std::optional<ImageSize> calibrationImageSize(const CommandOptions& o);

// Throws the loader's "does not exist" error for a PATH that is not there.
void requireCalibrationPath(const std::string& path);

// Loads --calib's PATH (a file, or a folder with a ROS or stereo_calib
// pair), with `imageSize` (0x0: none) for formats without one.
StereoCalibration loadCalibrationArg(const std::string& path, ImageSize imageSize = {});

// --ros-out DIR and --camera-name NAME (calibrate's table), checked before
// any slow work.
struct RosOutput {
  std::optional<std::string> dir;
  std::string cameraName = "stereo";
};
RosOutput rosOutput(const CommandOptions& o);

// Writes DIR/left.yaml and DIR/right.yaml (ROS camera_info), creating DIR;
// prints what it wrote.
void writeRosPair(const StereoCalibration& calibration, const std::string& dir,
                  const std::string& cameraName);

// `horopter calibrate --convert IN --to ros|horopter -o OUT`: reads the
// calibration IN in any format and writes it as asked, with calibrate's
// options (--to, --convert-right, --image-size, --alpha, --camera-name, -o).
int runCalibrationConversion(const std::string& in, const CommandOptions& o);

}  // namespace horopter::cli
