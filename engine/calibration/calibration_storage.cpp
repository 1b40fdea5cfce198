#include "calibration/calibration_storage.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <opencv2/core.hpp>

#include "calibration/yaml_structure.hpp"
#include "horopter/core/error.hpp"

namespace horopter::detail {

namespace {

// Calibration files are a few kilobytes; a larger one is not a calibration.
constexpr std::uintmax_t kMaxFileBytes = 16u << 20;

std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot open calibration file '" + path + "'");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The text as OpenCV's in-memory reader takes it: XML, JSON and YAML with
// its "%YAML" directive as they are, any other text as YAML (ROS's
// camera_info files start with their first field). YAML is checked first
// for what hangs OpenCV 4.6's parser (yaml_structure.hpp).
std::string forOpenCv(const std::string& text, const std::string& path) {
  const std::size_t start = text.find_first_not_of(" \t\r\n");
  const bool xmlOrJson =
      start != std::string::npos && (text.compare(start, 5, "<?xml") == 0 || text[start] == '{');
  if (xmlOrJson) return text;
  checkOneYamlDocument(text, path);
  if (start != std::string::npos && text.compare(start, 5, "%YAML") == 0) return text;
  return "%YAML:1.0\n" + text;
}

}  // namespace

CalibrationStorage::CalibrationStorage(const std::string& path) : path_(path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec))
    throw Error("calibration file '" + path + "' does not exist: run horopter calibrate first");
  const bool compressed = path.size() >= 3 && path.compare(path.size() - 3, 3, ".gz") == 0;
  if (!compressed && std::filesystem::file_size(path, ec) > kMaxFileBytes)
    throw Error("calibration file '" + path + "' is larger than 16 MiB: not a calibration");
  try {
    if (compressed)
      fs_.open(path, cv::FileStorage::READ);
    else
      fs_.open(forOpenCv(readText(path), path), cv::FileStorage::READ | cv::FileStorage::MEMORY);
  } catch (const cv::Exception& e) {
    throw Error("calibration file '" + path + "' is not valid OpenCV YAML/XML: " + e.msg);
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    // OpenCV's parsers let std::length_error out for some malformed text
    // (found by tests/fuzz/calibration_file_fuzz.cpp).
    throw Error("calibration file '" + path + "' is not valid OpenCV YAML/XML (" + e.what() + ")");
  }
  if (!fs_.isOpened())
    throw Error("cannot open calibration file '" + path + "' as OpenCV YAML/XML");
  // A top level that is a list or a value: OpenCV asserts on fs_[name]
  // (found by tests/fuzz/calibration_file_fuzz.cpp).
  if (!fs_.root().isMap())
    throw Error("calibration file '" + path + "' does not hold named fields at the top level");
}

const char* CalibrationStorage::firstOf(std::initializer_list<const char*> names) const {
  for (const char* n : names)
    if (has(n)) return n;
  return nullptr;
}

std::vector<std::string> CalibrationStorage::keys() const {
  return fs_.root().keys();
}

void CalibrationStorage::fail(const std::string& field, const std::string& what) const {
  std::ostringstream message;
  message << "calibration file '" << path_ << "': field '" << field << "' " << what << "; "
          << advice_;
  throw Error(message.str());
}

cv::FileNode CalibrationStorage::node(const char* name, const char* expected) const {
  const cv::FileNode n = fs_[name];
  if (n.empty()) fail(name, std::string("is missing (expected ") + expected + ")");
  return n;
}

double CalibrationStorage::number(const char* name) const {
  const cv::FileNode n = node(name, "a number");
  if (!n.isReal() && !n.isInt()) fail(name, "is not a number");
  return static_cast<double>(n);
}

int CalibrationStorage::integer(const char* name) const {
  const cv::FileNode n = node(name, "an integer");
  if (!n.isInt()) fail(name, "is not an integer");
  return static_cast<int>(n);
}

std::string CalibrationStorage::text(const char* name) const {
  const cv::FileNode n = node(name, "a string");
  if (!n.isString()) fail(name, "is not a string");
  return static_cast<std::string>(n);
}

cv::Mat CalibrationStorage::matrix(const char* name, int rows, int cols) const {
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

cv::Mat CalibrationStorage::vector(const char* name, int minLength, int maxLength) const {
  std::ostringstream expected;
  expected << "a vector of " << minLength;
  if (maxLength != minLength) expected << ".." << maxLength;
  expected << " numbers (1xN or Nx1 OpenCV matrix)";
  const cv::FileNode n = node(name, expected.str().c_str());
  if (!n.isMap() || !n["rows"].isInt() || !n["cols"].isInt())
    fail(name, "is not an OpenCV matrix (expected " + expected.str() + ")");
  const int rows = static_cast<int>(n["rows"]), cols = static_cast<int>(n["cols"]);
  const int length = rows == 1 ? cols : cols == 1 ? rows : -1;
  if (length < minLength || length > maxLength)
    fail(name, "is " + std::to_string(rows) + "x" + std::to_string(cols) + ", expected " +
                   expected.str());
  const cv::Mat m = rows == 1 ? matrix(name, 1, cols) : matrix(name, rows, 1);
  return m.reshape(1, 1);
}

cv::Mat CalibrationStorage::rosMatrix(const char* name, int rows, int cols) const {
  std::ostringstream expected;
  expected << "a map {rows: " << rows << ", cols: " << (cols ? std::to_string(cols) : "N")
           << ", data: [...]}";
  const cv::FileNode n = node(name, expected.str().c_str());
  if (!n.isMap()) fail(name, "is not " + expected.str());
  const cv::FileNode r = n["rows"], c = n["cols"], data = n["data"];
  if (!r.isInt() || !c.isInt()) fail(name, "has no integer rows and cols");
  const int fileRows = static_cast<int>(r), fileCols = static_cast<int>(c);
  if (fileRows != rows || (cols ? fileCols != cols : fileCols < 0 || fileCols > 14))
    fail(name, "is " + std::to_string(fileRows) + "x" + std::to_string(fileCols) + ", expected " +
                   std::to_string(rows) + "x" +
                   (cols ? std::to_string(cols) : std::string("N (0..14)")));
  const std::size_t count = static_cast<std::size_t>(fileRows) * fileCols;
  if (count > 0 && !data.isSeq()) fail(name, "has no data list (expected data: [...])");
  if (count > 0 && data.size() != count)
    fail(name, "has " + std::to_string(data.size()) + " numbers in data, expected " +
                   std::to_string(fileRows) + "x" + std::to_string(fileCols) + " = " +
                   std::to_string(count));
  cv::Mat m(fileRows, fileCols, CV_64F);
  for (std::size_t i = 0; i < count; ++i) {
    const cv::FileNode v = data[static_cast<int>(i)];
    if (!v.isReal() && !v.isInt()) fail(name, "holds data that is not a number");
    m.ptr<double>()[i] = static_cast<double>(v);
  }
  if (count > 0 && !cv::checkRange(m)) fail(name, "holds a non-finite value");
  return m;
}

cv::Rect CalibrationStorage::rect(const char* name) const {
  const cv::FileNode n = node(name, "[x, y, width, height]");
  if (!n.isSeq() || n.size() != 4) fail(name, "is not [x, y, width, height]");
  for (int i = 0; i < 4; ++i)
    if (!n[i].isInt()) fail(name, "is not [x, y, width, height] of integers");
  return {static_cast<int>(n[0]), static_cast<int>(n[1]), static_cast<int>(n[2]),
          static_cast<int>(n[3])};
}

}  // namespace horopter::detail
