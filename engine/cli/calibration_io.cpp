#include "calibration_io.hpp"

#include <cstdio>
#include <filesystem>
#include <iostream>

#include "horopter/core/error.hpp"

namespace horopter::cli {

std::optional<ImageSize> calibrationImageSize(const CommandOptions& o) {
  const auto text = o.optionalText("--image-size");
  if (!text) return std::nullopt;
  return asUsageError([&] {
    return parseImageSize(*text, "--image-size", {1, 1}, {16384, 16384});
  });
}

RosOutput rosOutput(const CommandOptions& o) {
  RosOutput out;
  out.dir = o.optionalText("--ros-out");
  out.cameraName = o.text("--camera-name");
  // Written unquoted into YAML: a plain name only (writeRosCameraInfo's rule).
  if (out.cameraName.empty() ||
      out.cameraName.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                       "0123456789_-./") != std::string::npos)
    throw UsageError("--camera-name takes letters, digits and _ - . / only, got '" +
                     out.cameraName + "'");
  if (out.dir && out.dir->empty()) throw UsageError("--ros-out takes a folder");
  return out;
}

void requireCalibrationPath(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec))
    throw Error("calibration file '" + path + "' does not exist: run horopter calibrate first");
}

StereoCalibration loadCalibrationArg(const std::string& path, ImageSize imageSize) {
  CalibrationImport import;
  import.imageSize = {imageSize.width, imageSize.height};
  return loadStereoCalibration(path, import);
}

void writeRosPair(const StereoCalibration& c, const std::string& dir,
                  const std::string& cameraName) {
  std::filesystem::create_directories(dir);
  const std::string left = (std::filesystem::path(dir) / "left.yaml").string();
  const std::string right = (std::filesystem::path(dir) / "right.yaml").string();
  writeRosCameraInfo(c, left, right, cameraName);
  std::printf("wrote %s and %s (ROS camera_info)\n", left.c_str(), right.c_str());
}

int runCalibrationConversion(const std::string& in, const CommandOptions& o) {
  for (const char* flag : {"--left", "--right", "--board", "--square", "--min-views", "--ros-out"})
    if (o.given(flag))
      throw UsageError(std::string(flag) +
                       " is for calibrating; with --convert use --to, --convert-right, "
                       "--image-size, --alpha, --camera-name and -o");
  const auto to = o.optionalText("--to");
  CalibrationImport import;
  if (const auto right = o.optionalText("--convert-right")) import.right = *right;
  if (const auto size = calibrationImageSize(o)) import.imageSize = {size->width, size->height};
  import.alpha = o.number("--alpha");
  const RosOutput ros = rosOutput(o);
  if (in.empty()) throw UsageError("--convert takes the calibration to read");
  if (!to) throw UsageError("--convert needs --to horopter or --to ros");
  const std::string target = o.given("--out") ? o.text("--out")
                             : *to == "ros"   ? "ros"
                                              : "calib.yml";

  const StereoCalibration c = loadStereoCalibration(in, import);
  std::printf("read %s: %s calibration, %dx%d\n", in.c_str(), c.format.c_str(), c.imageSize.width,
              c.imageSize.height);
  if (*to == "ros") {
    writeRosPair(c, target, ros.cameraName);
  } else {
    const std::filesystem::path parent = std::filesystem::path(target).parent_path();
    if (!parent.empty()) std::filesystem::create_directories(parent);
    saveStereoCalibration(c, target);
    std::printf("wrote %s (Horopter calibration)\n", target.c_str());
  }
  return 0;
}

}  // namespace horopter::cli
