// Calibrations in and out on the command line: the --calib path every
// command takes (any format loadStereoCalibration reads), `horopter calibrate
// --convert` and `--ros-out`. See docs/calibration.md.
#pragma once

#include <optional>
#include <string>

#include "args.hpp"
#include "horopter/vision/calibration.hpp"

namespace horopter::cli {

// --image-size WxH, the image size for a calibration that gives none (the
// stereo_calib sample's pair); nullopt when absent.
std::optional<ImageSize> parseCalibrationImageSize(Args& args);

// Throws the loader's "does not exist" error for a PATH that is not there.
void requireCalibrationPath(const std::string& path);

// Loads --calib's PATH (a file, or a folder with a ROS or stereo_calib
// pair), with `imageSize` (0x0: none) for formats without one.
StereoCalibration loadCalibrationArg(const std::string& path, ImageSize imageSize = {});

// --ros-out DIR and --camera-name NAME, checked before any slow work.
struct RosOutput {
  std::optional<std::string> dir;
  std::string cameraName = "stereo";
};
RosOutput parseRosOutput(Args& args);

// Writes DIR/left.yaml and DIR/right.yaml (ROS camera_info), creating DIR;
// prints what it wrote.
void writeRosPair(const StereoCalibration& calibration, const std::string& dir,
                  const std::string& cameraName);

// `horopter calibrate --convert IN --to ros|horopter -o OUT`: reads the
// calibration IN in any format and writes it as asked. Parses the rest of
// the options itself.
int runCalibrationConversion(const std::string& in, Args& args);

// The help of --convert and --ros-out, for calibrate --help.
extern const char* const kCalibrationConversionHelp;

}  // namespace horopter::cli
