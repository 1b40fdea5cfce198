// Horopter's calibration file: OpenCV FileStorage (YAML or XML), one
// top-level field per quantity so that any cv::FileStorage user can read it
// back. The board and the quality figures are written only when the
// calibration has them (an imported calibration has neither).
#include <opencv2/core/persistence.hpp>
#include <string>

#include "calibration/calibration_formats.hpp"
#include "file_output.hpp"
#include "horopter/core/error.hpp"
#include "horopter/vision/calibration.hpp"

namespace horopter {

namespace {

constexpr int kFormatVersion = 1;

void writeRect(cv::FileStorage& fs, const char* name, const cv::Rect& r) {
  fs << name << "[" << r.x << r.y << r.width << r.height << "]";
}

bool hasBoard(const StereoCalibration& c) {
  return c.board.innerCorners.area() > 0 || c.board.squareSize != 0;
}

void writeQuality(cv::FileStorage& fs, const StereoCalibration& c) {
  fs << "rms" << c.rms << "rms_left" << c.rmsLeft << "rms_right" << c.rmsRight;
  fs << "epipolar_error" << c.epipolarError << "homography_error" << c.homographyError;
  fs << "views"
     << "[";
  for (std::size_t i = 0; i < c.views.size(); ++i) {
    fs << "{"
       << "name" << c.views[i].name << "left_error" << c.views[i].left << "right_error"
       << c.views[i].right;
    if (i < c.boardHomographies.size()) fs << "board_homography" << c.boardHomographies[i];
    fs << "}";
  }
  fs << "]";
  fs << "skipped"
     << "[";
  for (const std::string& s : c.skipped)
    fs << s;
  fs << "]";
}

double optionalNumber(const detail::CalibrationStorage& in, const char* name) {
  return in.has(name) ? in.number(name) : 0.0;
}

void readViews(detail::CalibrationStorage& in, StereoCalibration& c) {
  // OpenCV asserts on a malformed node (a matrix whose data does not fill it,
  // found by tests/fuzz/calibration_file_fuzz.cpp): an error naming the field.
  const char* field = "views";
  try {
    for (const cv::FileNode& v : in.storage()["views"]) {
      c.views.push_back({static_cast<std::string>(v["name"]), static_cast<double>(v["left_error"]),
                         static_cast<double>(v["right_error"])});
      cv::Mat h;
      const cv::FileNode hn = v["board_homography"];
      if (hn.isMap() && !(hn["rows"].isInt() && static_cast<int>(hn["rows"]) == 3 &&
                          hn["cols"].isInt() && static_cast<int>(hn["cols"]) == 3))
        in.fail("views", "holds a board_homography that is not a 3x3 matrix");
      hn >> h;
      if (!h.empty()) c.boardHomographies.push_back(h);
    }
    field = "skipped";
    for (const cv::FileNode& s : in.storage()["skipped"])
      c.skipped.push_back(static_cast<std::string>(s));
  } catch (const Error&) {
    throw;  // already names the field
  } catch (const cv::Exception& e) {
    in.fail(field, "is malformed (" + e.err + ")");
  } catch (const std::exception& e) {
    in.fail(field, std::string("is malformed (") + e.what() + ")");
  }
}

}  // namespace

void saveStereoCalibration(const StereoCalibration& c, const std::string& path) {
  // Written in memory (the format from the name, as OpenCV picks it for a
  // file), then to the file with every write checked: cv::FileStorage
  // reports no failed write.
  if (path.size() >= 3 && path.compare(path.size() - 3, 3, ".gz") == 0)
    throw Error("cannot write the calibration file '" + path +
                "': compressed files are not written; use a name ending in .yml, .yaml or .xml");
  cv::FileStorage fs;
  try {
    fs.open(path, cv::FileStorage::WRITE | cv::FileStorage::MEMORY);
  } catch (const cv::Exception& e) {
    throw Error("cannot write the calibration file '" + path + "': " + e.msg);
  }
  if (!fs.isOpened())
    throw Error("cannot write the calibration file '" + path +
                "': use a name ending in .yml, .yaml or .xml");
  fs << "horopter_calibration_version" << kFormatVersion;
  if (!c.format.empty() && c.format != "horopter") fs << "imported_from" << c.format;
  fs << "image_width" << c.imageSize.width << "image_height" << c.imageSize.height;
  if (hasBoard(c))
    fs << "board_width" << c.board.innerCorners.width << "board_height"
       << c.board.innerCorners.height << "square_size" << c.board.squareSize;
  fs << "K1" << c.K1 << "D1" << c.D1 << "K2" << c.K2 << "D2" << c.D2;
  fs << "R" << c.R << "T" << c.T << "E" << c.E << "F" << c.F;
  fs << "R1" << c.R1 << "R2" << c.R2 << "P1" << c.P1 << "P2" << c.P2 << "Q" << c.Q;
  writeRect(fs, "roi1", c.roi1);
  writeRect(fs, "roi2", c.roi2);
  fs << "alpha" << c.alpha;
  if (!c.views.empty()) writeQuality(fs, c);
  detail::writeFile(path, fs.releaseAndGetString(), "calibration file");
}

namespace detail {

StereoCalibration readHoropterFile(CalibrationStorage& in) {
  StereoCalibration c;
  const int version = in.integer("horopter_calibration_version");
  if (version != kFormatVersion)
    in.fail("horopter_calibration_version", "is " + std::to_string(version) +
                                                " but this build reads version " +
                                                std::to_string(kFormatVersion));
  c.format = in.has("imported_from") ? in.text("imported_from") : "horopter";
  c.imageSize = {in.integer("image_width"), in.integer("image_height")};
  if (c.imageSize.width <= 0 || c.imageSize.height <= 0)
    in.fail("image_width", "and image_height must be positive");
  // The board only where the calibration came from board views.
  if (in.firstOf({"board_width", "board_height", "square_size"})) {
    c.board.innerCorners = {in.integer("board_width"), in.integer("board_height")};
    c.board.squareSize = in.number("square_size");
  }
  c.K1 = in.matrix("K1", 3, 3);
  c.D1 = in.matrix("D1", 1, 0);
  c.K2 = in.matrix("K2", 3, 3);
  c.D2 = in.matrix("D2", 1, 0);
  c.R = in.matrix("R", 3, 3);
  c.T = in.matrix("T", 3, 1);
  c.E = in.matrix("E", 3, 3);
  c.F = in.matrix("F", 3, 3);
  c.R1 = in.matrix("R1", 3, 3);
  c.R2 = in.matrix("R2", 3, 3);
  c.P1 = in.matrix("P1", 3, 4);
  c.P2 = in.matrix("P2", 3, 4);
  c.Q = in.matrix("Q", 4, 4);
  c.roi1 = in.rect("roi1");
  c.roi2 = in.rect("roi2");
  c.alpha = in.number("alpha");
  c.rms = optionalNumber(in, "rms");
  c.rmsLeft = optionalNumber(in, "rms_left");
  c.rmsRight = optionalNumber(in, "rms_right");
  c.epipolarError = optionalNumber(in, "epipolar_error");
  c.homographyError = optionalNumber(in, "homography_error");
  readViews(in, c);
  return c;
}

}  // namespace detail

}  // namespace horopter
