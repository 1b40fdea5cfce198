#include "calibration_io.hpp"

#include <cstdio>
#include <filesystem>
#include <iostream>

#include "horopter/core/error.hpp"

namespace horopter::cli {

const char* const kCalibrationConversionHelp =
    "\nOr: horopter calibrate --convert IN --to horopter|ros [-o OUT] [--image-size WxH]\n\n"
    "Calibrations from elsewhere and to ROS (formats: docs/calibration.md):\n"
    "  --ros-out DIR     also write DIR/left.yaml and DIR/right.yaml, ROS camera_info files\n"
    "  --camera-name N   camera_name in the ROS files: N/left, N/right (default stereo)\n"
    "  --convert IN      instead of calibrating, read the calibration IN and write it with\n"
    "                    --to; IN: Horopter's file, an OpenCV file (K1, D1, K2, D2, R, T), the\n"
    "                    stereo_calib sample's intrinsics.yml (+ extrinsics.yml), a ROS\n"
    "                    camera_info left.yaml (+ right.yaml), or a folder holding a pair\n"
    "  --convert-right F the pair's second file where it is not named like the first\n"
    "                    (left -> right, intrinsics -> extrinsics)\n"
    "  --to FORMAT       horopter (-o FILE, default calib.yml) or ros (-o DIR, default ros)\n"
    "  --image-size WxH  the image size, for a calibration that gives none (stereo_calib)\n"
    "  --alpha A         with --convert: rectification scaling where IN has no R1..Q\n";

std::optional<ImageSize> parseCalibrationImageSize(Args& args) {
  const auto text = args.value("--image-size");
  if (!text) return std::nullopt;
  return parseImageSize(*text, "--image-size", {1, 1}, {16384, 16384});
}

RosOutput parseRosOutput(Args& args) {
  RosOutput out;
  out.dir = args.value("--ros-out");
  out.cameraName = args.stringValue("--camera-name", out.cameraName);
  // Written unquoted into YAML: a plain name only (writeRosCameraInfo's rule).
  if (out.cameraName.empty() ||
      out.cameraName.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                       "0123456789_-./") != std::string::npos)
    throw Error("--camera-name takes letters, digits and _ - . / only, got '" + out.cameraName +
                "'");
  if (out.dir && out.dir->empty()) throw Error("--ros-out takes a folder");
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

int runCalibrationConversion(const std::string& in, Args& args) {
  const auto to = args.value("--to");
  auto out = args.value("-o");
  if (!out) out = args.value("--out");
  CalibrationImport import;
  if (const auto right = args.value("--convert-right")) import.right = *right;
  if (const auto size = parseCalibrationImageSize(args))
    import.imageSize = {size->width, size->height};
  import.alpha = args.doubleValue("--alpha", 0.0, -1.0, 1.0);
  const RosOutput ros = parseRosOutput(args);
  if (ros.dir) throw Error("--ros-out is for calibrating; with --convert use --to ros -o DIR");
  args.finish("calibrate --convert");
  if (in.empty()) throw Error("--convert takes the calibration to read");
  if (!to) throw Error("--convert needs --to horopter or --to ros");
  if (*to != "horopter" && *to != "ros")
    throw Error("--to takes horopter or ros, got '" + *to + "'");
  const std::string target = out ? *out : *to == "ros" ? "ros" : "calib.yml";

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
