// loadStereoCalibration: the format recognised by content, the partner file
// of a pair found, what a format lacks computed, and every calibration
// checked for meaning (calibration_checks.hpp) whatever its source.
#include <cctype>
#include <filesystem>
#include <opencv2/calib3d.hpp>
#include <optional>
#include <sstream>
#include <string>

#include "calibration/calibration_checks.hpp"
#include "calibration/calibration_formats.hpp"
#include "horopter/core/error.hpp"
#include "horopter/vision/calibration.hpp"

namespace horopter {

namespace detail {

namespace {

namespace fs = std::filesystem;

enum class Kind { Horopter, OpenCvStereo, OpenCvIntrinsics, OpenCvExtrinsics, Ros, OneCamera };

// Field names other tools use for the same matrices (OpenCV's stereo_calib
// sample: M1, M2; cv2.stereoCalibrate's argument names).
const char* cameraMatrix1(const CalibrationStorage& s) {
  return s.firstOf({"K1", "M1", "cameraMatrix1"});
}
const char* cameraMatrix2(const CalibrationStorage& s) {
  return s.firstOf({"K2", "M2", "cameraMatrix2"});
}
const char* distortion1(const CalibrationStorage& s) {
  return s.firstOf({"D1", "distCoeffs1"});
}
const char* distortion2(const CalibrationStorage& s) {
  return s.firstOf({"D2", "distCoeffs2"});
}

std::string fieldList(const CalibrationStorage& s) {
  std::ostringstream out;
  const std::vector<std::string> keys = s.keys();
  for (std::size_t i = 0; i < keys.size() && i < 12; ++i)
    out << (i ? ", " : "") << keys[i];
  if (keys.size() > 12) out << ", ...";
  return keys.empty() ? std::string("none") : out.str();
}

Kind kindOf(const CalibrationStorage& s) {
  if (s.has("horopter_calibration_version")) return Kind::Horopter;
  // ROS's camera_matrix is a plain map {rows, cols, data}; OpenCV's
  // calibration sample writes an opencv-matrix (with dt) under the same name.
  const cv::FileNode camera = s.get("camera_matrix");
  if (camera.isMap() && !camera["data"].empty() && camera["dt"].empty()) return Kind::Ros;
  const bool intrinsics = cameraMatrix1(s) != nullptr;
  const bool extrinsics = s.has("R") || s.has("T");
  if (intrinsics && extrinsics) return Kind::OpenCvStereo;
  if (intrinsics) return Kind::OpenCvIntrinsics;
  if (extrinsics) return Kind::OpenCvExtrinsics;
  if (s.firstOf({"camera_matrix", "cameraMatrix", "K"})) return Kind::OneCamera;
  throw Error("calibration file '" + s.path() +
              "' is no calibration Horopter recognises (its fields: " + fieldList(s) +
              "); it reads Horopter's file, OpenCV's (K1, D1, K2, D2, R, T), the stereo_calib "
              "sample's intrinsics.yml + extrinsics.yml and ROS camera_info pairs: see "
              "docs/calibration.md");
}

std::string upper(std::string s) {
  for (char& ch : s)
    ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  return s;
}

std::string capitalized(std::string s) {
  if (!s.empty()) s[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(s[0])));
  return s;
}

// `path` with the last `from` in its file name replaced by `to` (also as
// From -> To and FROM -> TO); nullopt when the name holds no `from`.
std::optional<std::string> swapInName(const std::string& path, const std::string& from,
                                      const std::string& to) {
  const fs::path p(path);
  const std::string name = p.filename().string();
  for (const auto& [f, t] : {std::pair{from, to}, std::pair{capitalized(from), capitalized(to)},
                             std::pair{upper(from), upper(to)}}) {
    const std::size_t at = name.rfind(f);
    if (at == std::string::npos) continue;
    std::string renamed = name;
    renamed.replace(at, f.size(), t);
    return (p.parent_path() / renamed).string();
  }
  return std::nullopt;
}

// The other file of a pair: import.right, else `path` renamed (from -> to).
std::string partnerOf(const std::string& path, const CalibrationImport& import,
                      const std::string& from, const std::string& to, const std::string& what) {
  if (!import.right.empty()) return import.right;
  const std::optional<std::string> other = swapInName(path, from, to);
  std::error_code ec;
  if (other && fs::exists(*other, ec)) return *other;
  throw Error("calibration file '" + path + "' " + what +
              (other ? " and '" + *other + "' does not exist" : std::string()) +
              ": give the other file too: a folder holding both as " + from + ".yaml and " + to +
              ".yaml (or .yml), horopter calibrate --convert-right FILE, or Python's right=");
}

// A folder: left.yaml + right.yaml, or intrinsics.yml + extrinsics.yml
// (each .yml, .yaml or .xml); the first file found of the pair.
std::string fileInFolder(const std::string& folder) {
  for (const char* stem : {"left", "intrinsics"})
    for (const char* ext : {".yaml", ".yml", ".xml"}) {
      const fs::path candidate = fs::path(folder) / (std::string(stem) + ext);
      std::error_code ec;
      if (fs::is_regular_file(candidate, ec)) return candidate.string();
    }
  throw Error("calibration folder '" + folder +
              "' holds neither left.yaml + right.yaml (ROS camera_info) nor intrinsics.yml + "
              "extrinsics.yml (OpenCV's stereo_calib): give a calibration file");
}

void checkImageSize(StereoCalibration& c, const CalibrationImport& import,
                    const std::string& source) {
  if (import.imageSize.empty() || import.imageSize == c.imageSize) return;
  std::ostringstream message;
  message << "calibration '" << source << "' is for " << c.imageSize.width << "x"
          << c.imageSize.height << " images, not " << import.imageSize.width << "x"
          << import.imageSize.height
          << " (the size given, or that of the images read): calibrate at the capture "
             "resolution";
  throw Error(message.str());
}

// The image size as OpenCV users store it: image_width + image_height
// (OpenCV's calibration sample), width + height, or [w, h] under
// image_size / imageSize / img_size (a cv::Size or a 1x2 matrix).
std::optional<cv::Size> imageSizeIn(const CalibrationStorage& s) {
  for (const auto& [w, h] :
       {std::pair{"image_width", "image_height"}, std::pair{"width", "height"}})
    if (s.has(w) || s.has(h)) return cv::Size(s.integer(w), s.integer(h));
  const char* name = s.firstOf({"image_size", "imageSize", "img_size"});
  if (!name) return std::nullopt;
  const cv::FileNode n = s.get(name);
  if (n.isSeq() && n.size() == 2 && n[0].isInt() && n[1].isInt())
    return cv::Size(static_cast<int>(n[0]), static_cast<int>(n[1]));
  const cv::Mat m = s.vector(name, 2, 2);
  const int width = static_cast<int>(m.at<double>(0)), height = static_cast<int>(m.at<double>(1));
  if (width != m.at<double>(0) || height != m.at<double>(1))
    s.fail(name, "is not [width, height] in whole pixels");
  return cv::Size(width, height);
}

}  // namespace

void computeEssentialAndFundamental(StereoCalibration& c) {
  const cv::Vec3d t(c.T);
  const cv::Matx33d tx(0, -t[2], t[1], t[2], 0, -t[0], -t[1], t[0], 0);
  const cv::Matx33d e = tx * cv::Matx33d(c.R);
  cv::Matx33d f = cv::Matx33d(c.K2).inv().t() * e * cv::Matx33d(c.K1).inv();
  if (f(2, 2) != 0) f *= 1.0 / f(2, 2);  // OpenCV's scale
  c.E = cv::Mat(e, true);
  c.F = cv::Mat(f, true);
}

void computeRectification(StereoCalibration& c, double alpha) {
  if (!(alpha == -1.0 || (alpha >= 0.0 && alpha <= 1.0)))
    throw Error("alpha must be in [0, 1] (or -1 for OpenCV's default scaling), got " +
                std::to_string(alpha));
  c.alpha = alpha;
  cv::stereoRectify(c.K1, c.D1, c.K2, c.D2, c.imageSize, c.R, c.T, c.R1, c.R2, c.P1, c.P2, c.Q,
                    cv::CALIB_ZERO_DISPARITY, alpha, c.imageSize, &c.roi1, &c.roi2);
}

StereoCalibration readOpenCvStereo(CalibrationStorage& intrinsics, CalibrationStorage& extrinsics,
                                   const CalibrationImport& import) {
  for (CalibrationStorage* s : {&intrinsics, &extrinsics})
    s->setAdvice("fix the file or export it again (see docs/calibration.md)");
  StereoCalibration c;
  c.format = &intrinsics == &extrinsics ? "opencv" : "opencv stereo_calib";
  const char* k1 = cameraMatrix1(intrinsics);
  const char* k2 = cameraMatrix2(intrinsics);
  const char* d1 = distortion1(intrinsics);
  const char* d2 = distortion2(intrinsics);
  c.K1 = intrinsics.matrix(k1 ? k1 : "K1", 3, 3);
  c.D1 = intrinsics.vector(d1 ? d1 : "D1", 4, 14);
  c.K2 = intrinsics.matrix(k2 ? k2 : "K2", 3, 3);
  c.D2 = intrinsics.vector(d2 ? d2 : "D2", 4, 14);
  if (!extrinsics.has("T"))
    extrinsics.fail("T",
                    "is missing: the file holds intrinsics only, and a stereo calibration "
                    "needs the extrinsics R and T (cv::stereoCalibrate's output)");
  c.R = extrinsics.matrix("R", 3, 3);
  c.T = extrinsics.vector("T", 3, 3).reshape(1, 3);

  std::optional<cv::Size> size = imageSizeIn(intrinsics);
  if (!size) size = imageSizeIn(extrinsics);
  if (size) {
    c.imageSize = *size;
    checkImageSize(c, import, intrinsics.path());
  } else if (!import.imageSize.empty()) {
    c.imageSize = import.imageSize;
  } else {
    throw Error("calibration file '" + intrinsics.path() +
                "' gives no image size (image_width + image_height, or image_size: [w, h]): pass "
                "it (--image-size WxH; Python: image_size=(w, h)), or add it to the file");
  }

  // Rectification as the file gives it (all of it), else as calibrateStereo
  // computes it.
  const char* rectification[] = {"R1", "R2", "P1", "P2", "Q"};
  int present = 0;
  for (const char* name : rectification)
    present += extrinsics.has(name) ? 1 : 0;
  if (present == 5) {
    c.R1 = extrinsics.matrix("R1", 3, 3);
    c.R2 = extrinsics.matrix("R2", 3, 3);
    c.P1 = extrinsics.matrix("P1", 3, 4);
    c.P2 = extrinsics.matrix("P2", 3, 4);
    c.Q = extrinsics.matrix("Q", 4, 4);
    c.roi1 = extrinsics.has("roi1")           ? extrinsics.rect("roi1")
             : extrinsics.has("validPixROI1") ? extrinsics.rect("validPixROI1")
                                              : cv::Rect({0, 0}, c.imageSize);
    c.roi2 = extrinsics.has("roi2")           ? extrinsics.rect("roi2")
             : extrinsics.has("validPixROI2") ? extrinsics.rect("validPixROI2")
                                              : cv::Rect({0, 0}, c.imageSize);
  } else if (present > 0) {
    for (const char* name : rectification)
      if (!extrinsics.has(name))
        extrinsics.fail(name,
                        "is missing: give all of R1, R2, P1, P2, Q or none (Horopter "
                        "then computes them with cv::stereoRectify)");
  } else {
    computeRectification(c, import.alpha);
  }
  computeEssentialAndFundamental(c);
  return c;
}

}  // namespace detail

StereoCalibration loadStereoCalibration(const std::string& requested,
                                        const CalibrationImport& import) {
  using detail::CalibrationStorage;
  using detail::Kind;
  std::error_code ec;
  const std::string path =
      std::filesystem::is_directory(requested, ec) ? detail::fileInFolder(requested) : requested;
  CalibrationStorage first(path);
  const Kind kind = detail::kindOf(first);
  const auto noSecondFile = [&](const char* what) {
    if (!import.right.empty())
      throw Error("calibration file '" + path + "' is " + what +
                  " in one file: give no second file ('" + import.right + "')");
  };
  StereoCalibration c;
  std::string source = path;
  switch (kind) {
    case Kind::Horopter:
      noSecondFile("a complete Horopter calibration");
      c = detail::readHoropterFile(first);
      detail::checkImageSize(c, import, path);
      break;
    case Kind::OpenCvStereo:
      noSecondFile("a complete OpenCV stereo calibration");
      c = detail::readOpenCvStereo(first, first, import);
      break;
    case Kind::OpenCvIntrinsics:
    case Kind::OpenCvExtrinsics: {
      const bool intrinsicsFirst = kind == Kind::OpenCvIntrinsics;
      const std::string other =
          intrinsicsFirst
              ? detail::partnerOf(path, import, "intrinsics", "extrinsics",
                                  "holds the intrinsics but no extrinsics (R, T)")
              : detail::partnerOf(path, import, "extrinsics", "intrinsics",
                                  "holds the extrinsics but no intrinsics K1, D1, K2, D2");
      CalibrationStorage second(other);
      if (detail::kindOf(second) !=
          (intrinsicsFirst ? Kind::OpenCvExtrinsics : Kind::OpenCvIntrinsics))
        throw Error("calibration file '" + other + "' is not the " +
                    (intrinsicsFirst ? "extrinsics (R, T)" : "intrinsics (M1, D1, M2, D2)") +
                    " to go with '" + path + "'");
      c = intrinsicsFirst ? detail::readOpenCvStereo(first, second, import)
                          : detail::readOpenCvStereo(second, first, import);
      source = path + "' + '" + other;
      break;
    }
    case Kind::Ros: {
      // The given file is the left one unless it is named as the right one
      // and the partner is to be found.
      // This file's fields first: its own errors before any about its partner.
      const detail::RosCameraInfo a = detail::readRosCameraInfo(first);
      const bool givenRight = import.right.empty() &&
                              !detail::swapInName(path, "left", "right").has_value() &&
                              detail::swapInName(path, "right", "left").has_value();
      const std::string other =
          givenRight
              ? detail::partnerOf(path, import, "right", "left",
                                  "is one camera's ROS camera_info (the right one)")
              : detail::partnerOf(path, import, "left", "right", "is one camera's ROS camera_info");
      CalibrationStorage second(other);
      if (detail::kindOf(second) != Kind::Ros)
        throw Error("calibration file '" + other +
                    "' is not a ROS camera_info file to pair with '" + path + "'");
      const detail::RosCameraInfo b = detail::readRosCameraInfo(second);
      c = givenRight ? detail::stereoFromRos(b, a) : detail::stereoFromRos(a, b);
      source = givenRight ? other + "' + '" + path : path + "' + '" + other;
      detail::checkImageSize(c, import, source);
      break;
    }
    case Kind::OneCamera:
      throw Error("calibration file '" + path +
                  "' holds one camera's intrinsics and no extrinsics (no R, T): a stereo "
                  "calibration needs both cameras and where the right one is; calibrate the "
                  "pair (horopter calibrate, cv::stereoCalibrate)");
  }
  checkCalibration(c, source);  // the meanings, once the structure is read
  return c;
}

}  // namespace horopter
