// A calibration file opened for reading, whatever wrote it (Horopter,
// OpenCV's cv::FileStorage, ROS's camera_info files), with typed accessors
// whose failures name the file and the field. The structure is read here;
// the meanings are checked by calibration_checks.hpp.
#pragma once

#include <initializer_list>
#include <opencv2/core/persistence.hpp>
#include <string>
#include <vector>

namespace horopter::detail {

class CalibrationStorage {
 public:
  // Throws horopter::Error for a missing file, text no OpenCV parser reads,
  // or a top level that is not a map. Files without a "%YAML" directive
  // (ROS writes none) are read as YAML: OpenCV refuses them by path.
  explicit CalibrationStorage(const std::string& path);

  const std::string& path() const { return path_; }
  // The advice ending every failure ("re-run horopter calibrate ...").
  void setAdvice(std::string advice) { advice_ = std::move(advice); }

  bool has(const char* name) const { return !fs_[name].empty(); }
  cv::FileNode get(const char* name) const { return fs_[name]; }
  // The first of `names` present; nullptr when none is.
  const char* firstOf(std::initializer_list<const char*> names) const;
  // The top-level field names, in file order (for "found: ..." messages).
  std::vector<std::string> keys() const;

  [[noreturn]] void fail(const std::string& field, const std::string& what) const;
  cv::FileNode node(const char* name, const char* expected) const;

  double number(const char* name) const;
  int integer(const char* name) const;
  std::string text(const char* name) const;
  // An OpenCV matrix ("!!opencv-matrix") of rows x cols, as CV_64F;
  // cols = 0 accepts any row vector of 1..14 entries.
  cv::Mat matrix(const char* name, int rows, int cols) const;
  // An OpenCV matrix holding a vector of minLength..maxLength entries, as a
  // row (1xN) or a column (Nx1): returned as a CV_64F row.
  cv::Mat vector(const char* name, int minLength, int maxLength) const;
  // A ROS matrix: a map {rows, cols, data: [...]} with rows*cols numbers;
  // cols = 0 accepts 0..14 columns (a distortion vector).
  cv::Mat rosMatrix(const char* name, int rows, int cols) const;
  cv::Rect rect(const char* name) const;

  cv::FileStorage& storage() { return fs_; }

 private:
  std::string path_;
  std::string advice_ = "re-run horopter calibrate to write a complete file";
  cv::FileStorage fs_;
};

}  // namespace horopter::detail
