// The calibration file: OpenCV FileStorage (YAML or XML), one top-level field
// per quantity so that any cv::FileStorage user can read it back.
#include <filesystem>
#include <opencv2/core/persistence.hpp>
#include <string>

#include "calibration/calibration_checks.hpp"
#include "file_output.hpp"
#include "horopter/core/error.hpp"
#include "horopter/vision/calibration.hpp"

namespace horopter {

namespace {

constexpr int kFormatVersion = 1;

void writeRect(cv::FileStorage& fs, const char* name, const cv::Rect& r) {
  fs << name << "[" << r.x << r.y << r.width << r.height << "]";
}

class Reader {
 public:
  explicit Reader(const std::string& path) : path_(path) {
    if (!std::filesystem::exists(path))
      throw Error("calibration file '" + path + "' does not exist: run horopter calibrate first");
    try {
      fs_.open(path, cv::FileStorage::READ);
    } catch (const cv::Exception& e) {
      throw Error("calibration file '" + path + "' is not valid OpenCV YAML/XML: " + e.msg);
    } catch (const std::exception& e) {
      // OpenCV's parsers let std::length_error out for some malformed text
      // (found by tests/fuzz/calibration_file_fuzz.cpp).
      throw Error("calibration file '" + path + "' is not valid OpenCV YAML/XML (" + e.what() +
                  ")");
    }
    if (!fs_.isOpened())
      throw Error("cannot open calibration file '" + path + "' as OpenCV YAML/XML");
    // A top level that is a list or a value: OpenCV asserts on fs_[name]
    // (found by tests/fuzz/calibration_file_fuzz.cpp).
    if (!fs_.root().isMap())
      throw Error("calibration file '" + path + "' does not hold named fields at the top level");
  }

  cv::FileNode node(const char* name, const char* expected) {
    const cv::FileNode n = fs_[name];
    if (n.empty()) fail(name, std::string("is missing (expected ") + expected + ")");
    return n;
  }

  [[noreturn]] void fail(const std::string& field, const std::string& what) const {
    throw Error("calibration file '" + path_ + "': field '" + field + "' " + what +
                "; re-run horopter calibrate to write a complete file");
  }

  double number(const char* name) {
    const cv::FileNode n = node(name, "a number");
    if (!n.isReal() && !n.isInt()) fail(name, "is not a number");
    return static_cast<double>(n);
  }

  int integer(const char* name) {
    const cv::FileNode n = node(name, "an integer");
    if (!n.isInt()) fail(name, "is not an integer");
    return static_cast<int>(n);
  }

  // A matrix of `rows` x `cols` doubles; cols = 0 accepts any row vector.
  cv::Mat matrix(const char* name, int rows, int cols) {
    const std::string expected =
        std::to_string(rows) + "x" + (cols ? std::to_string(cols) : std::string("N")) + " matrix";
    const cv::FileNode n = node(name, expected.c_str());
    // The header's size first: OpenCV allocates rows x cols before reading
    // the data, so "rows: 2000000000" would allocate gigabytes, or fail
    // inside OpenCV, before the size check below (found by the fuzz target
    // tests/fuzz/calibration_file_fuzz.cpp). A row vector has at most 14
    // entries, OpenCV's longest distortion model.
    if (n.isMap()) {
      const cv::FileNode r = n["rows"], c = n["cols"];
      if (!r.isInt() || !c.isInt())
        fail(name, "is not an OpenCV matrix (expected a " + expected + ")");
      const int fileRows = static_cast<int>(r), fileCols = static_cast<int>(c);
      if (fileRows != rows || (cols ? fileCols != cols : fileCols < 1 || fileCols > 14))
        fail(name, "is " + std::to_string(fileRows) + "x" + std::to_string(fileCols) +
                       ", expected a " + expected);
    }
    cv::Mat m;
    try {
      n >> m;
    } catch (const std::exception&) {  // cv::Exception, or std:: from OpenCV's reader
      fail(name, "is not an OpenCV matrix (expected a " + expected + ")");
    }
    if (m.empty() || m.rows != rows || (cols && m.cols != cols) || m.channels() != 1)
      fail(name, "is " + std::to_string(m.rows) + "x" + std::to_string(m.cols) + ", expected a " +
                     expected);
    m.convertTo(m, CV_64F);
    if (!cv::checkRange(m)) fail(name, "holds a non-finite value");
    return m;
  }

  cv::Rect rect(const char* name) {
    const cv::FileNode n = node(name, "[x, y, width, height]");
    if (!n.isSeq() || n.size() != 4) fail(name, "is not [x, y, width, height]");
    return {static_cast<int>(n[0]), static_cast<int>(n[1]), static_cast<int>(n[2]),
            static_cast<int>(n[3])};
  }

  cv::FileStorage& storage() { return fs_; }

 private:
  std::string path_;
  cv::FileStorage fs_;
};

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
  fs << "image_width" << c.imageSize.width << "image_height" << c.imageSize.height;
  fs << "board_width" << c.board.innerCorners.width << "board_height" << c.board.innerCorners.height
     << "square_size" << c.board.squareSize;
  fs << "K1" << c.K1 << "D1" << c.D1 << "K2" << c.K2 << "D2" << c.D2;
  fs << "R" << c.R << "T" << c.T << "E" << c.E << "F" << c.F;
  fs << "R1" << c.R1 << "R2" << c.R2 << "P1" << c.P1 << "P2" << c.P2 << "Q" << c.Q;
  writeRect(fs, "roi1", c.roi1);
  writeRect(fs, "roi2", c.roi2);
  fs << "alpha" << c.alpha;
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
  detail::writeFile(path, fs.releaseAndGetString(), "calibration file");
}

StereoCalibration loadStereoCalibration(const std::string& path) {
  Reader in(path);
  StereoCalibration c;
  const int version = in.integer("horopter_calibration_version");
  if (version != kFormatVersion)
    in.fail("horopter_calibration_version", "is " + std::to_string(version) +
                                                " but this build reads version " +
                                                std::to_string(kFormatVersion));
  c.imageSize = {in.integer("image_width"), in.integer("image_height")};
  if (c.imageSize.width <= 0 || c.imageSize.height <= 0)
    in.fail("image_width", "and image_height must be positive");
  c.board.innerCorners = {in.integer("board_width"), in.integer("board_height")};
  c.board.squareSize = in.number("square_size");
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
  c.rms = in.number("rms");
  c.rmsLeft = in.number("rms_left");
  c.rmsRight = in.number("rms_right");
  c.epipolarError = in.number("epipolar_error");
  c.homographyError = in.number("homography_error");
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
  checkCalibration(c, path);  // the meanings, once the structure is read
  return c;
}

}  // namespace horopter
