// Calibration from chessboard views (what `horopter calibrate` does), the
// calibration files, the rectified geometry they give, and rectification of
// captured pairs.
#include <pybind11/stl.h>

#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "arrays.hpp"
#include "bindings.hpp"
#include "horopter/core/error.hpp"
#include "horopter/vision/calibration.hpp"

namespace horopter::python {

namespace {

// A small matrix as a new float64 array (a copy: calibration matrices are tiny).
py::object matrix(const cv::Mat& m) {
  if (m.empty()) return py::none();
  cv::Mat d;
  m.convertTo(d, CV_64F);
  return shareMat(d);
}

cv::Size boardSize(const py::sequence& innerCorners) {
  if (innerCorners.size() != 2)
    throw Error("inner_corners takes (corners per row, corners per column), e.g. (9, 6)");
  const cv::Size size(innerCorners[0].cast<int>(), innerCorners[1].cast<int>());
  if (size.width < 2 || size.height < 2)
    throw Error("inner_corners must be at least (2, 2), got (" + std::to_string(size.width) + ", " +
                std::to_string(size.height) + ")");
  return size;
}

// A grey or BGR image from Python, as a Mat over its memory.
cv::Mat boardImage(py::handle image, const std::string& what) {
  return matOver(inputView(image, {PixelType::U8C1, PixelType::U8C3}, what));
}

// findBoardCorners: an (N, 2) float32 array, or None where the whole board
// is not in view.
py::object findCorners(py::handle image, const py::sequence& innerCorners) {
  const cv::Mat m = boardImage(image, "image");
  const cv::Size size = boardSize(innerCorners);
  std::vector<cv::Point2f> corners;
  {
    py::gil_scoped_release release;
    corners = findBoardCorners(m, size);
  }
  if (corners.empty()) return py::none();
  cv::Mat points(static_cast<int>(corners.size()), 2, CV_32F, corners.data());
  return shareMat(points.clone());
}

// detectBoards + calibrateStereo over lists of images (same order: pair i
// is lefts[i] and rights[i]).
StereoCalibration calibrate(const py::sequence& lefts, const py::sequence& rights,
                            double squareSize, const py::sequence& innerCorners, int minViews,
                            double alpha) {
  if (lefts.size() != rights.size())
    throw Error("calibrate: " + std::to_string(lefts.size()) + " left images but " +
                std::to_string(rights.size()) + " right images; give them in pairs");
  BoardSpec board;
  board.innerCorners = boardSize(innerCorners);
  board.squareSize = squareSize;
  CalibrationOptions options;
  options.minViews = minViews;
  options.alpha = alpha;
  std::vector<StereoImagePair> pairs;
  for (std::size_t i = 0; i < lefts.size(); ++i) {
    const std::string name = "pair " + std::to_string(i);
    pairs.push_back({name, boardImage(lefts[i], name + " left image"),
                     boardImage(rights[i], name + " right image")});
  }
  py::gil_scoped_release release;
  return calibrateStereo(detectBoards(pairs, board.innerCorners), board, options);
}

// loadStereoCalibration with Python's optional arguments.
StereoCalibration loadCalibration(const std::string& path, const std::optional<std::string>& right,
                                  const std::optional<py::sequence>& imageSize, double alpha) {
  CalibrationImport import;
  if (right) import.right = *right;
  if (imageSize) {
    if (imageSize->size() != 2)
      throw Error("image_size takes (width, height) in pixels, e.g. (640, 480)");
    import.imageSize = {(*imageSize)[0].cast<int>(), (*imageSize)[1].cast<int>()};
    if (import.imageSize.width < 1 || import.imageSize.height < 1)
      throw Error("image_size must be positive, got (" + std::to_string(import.imageSize.width) +
                  ", " + std::to_string(import.imageSize.height) + ")");
  }
  import.alpha = alpha;
  py::gil_scoped_release release;
  return loadStereoCalibration(path, import);
}

py::tuple rect(const cv::Rect& r) {
  return py::make_tuple(r.x, r.y, r.width, r.height);
}

class Rectifier {
 public:
  explicit Rectifier(const StereoCalibration& c) : rectifier_(c) {}

  py::tuple rectify(py::handle left, py::handle right) {
    const cv::Mat l = matOver(inputView(left, {PixelType::U8C1, PixelType::U8C3}, "left image"));
    const cv::Mat r = matOver(inputView(right, {PixelType::U8C1, PixelType::U8C3}, "right image"));
    cv::Mat outLeft, outRight;
    {
      // The lock only with the GIL released (see StereoMatcher in bind_stereo.cpp).
      py::gil_scoped_release release;
      std::lock_guard lock(mutex_);
      rectifier_.rectify(l, r);
      // The rectifier reuses its buffers on the next call.
      outLeft = rectifier_.left().clone();
      outRight = rectifier_.right().clone();
    }
    return py::make_tuple(shareMat(outLeft), shareMat(outRight));
  }
  py::tuple imageSize() const {
    return py::make_tuple(rectifier_.imageSize().width, rectifier_.imageSize().height);
  }

 private:
  StereoRectifier rectifier_;
  std::mutex mutex_;
};

}  // namespace

void bindCalibration(py::module_& m) {
  py::class_<StereoCalibration>(m, "StereoCalibration",
                                "A stereo calibration (OpenCV's conventions): intrinsics, "
                                "extrinsics, rectification, quality figures")
      .def_property_readonly("image_size",
                             [](const StereoCalibration& c) {
                               return py::make_tuple(c.imageSize.width, c.imageSize.height);
                             })
      .def_property_readonly("K1", [](const StereoCalibration& c) { return matrix(c.K1); })
      .def_property_readonly("D1", [](const StereoCalibration& c) { return matrix(c.D1); })
      .def_property_readonly("K2", [](const StereoCalibration& c) { return matrix(c.K2); })
      .def_property_readonly("D2", [](const StereoCalibration& c) { return matrix(c.D2); })
      .def_property_readonly("R", [](const StereoCalibration& c) { return matrix(c.R); })
      .def_property_readonly("T", [](const StereoCalibration& c) { return matrix(c.T); })
      .def_property_readonly("E", [](const StereoCalibration& c) { return matrix(c.E); })
      .def_property_readonly("F", [](const StereoCalibration& c) { return matrix(c.F); })
      .def_property_readonly("R1", [](const StereoCalibration& c) { return matrix(c.R1); })
      .def_property_readonly("R2", [](const StereoCalibration& c) { return matrix(c.R2); })
      .def_property_readonly("P1", [](const StereoCalibration& c) { return matrix(c.P1); })
      .def_property_readonly("P2", [](const StereoCalibration& c) { return matrix(c.P2); })
      .def_property_readonly("Q", [](const StereoCalibration& c) { return matrix(c.Q); })
      .def_property_readonly("roi1", [](const StereoCalibration& c) { return rect(c.roi1); })
      .def_property_readonly("roi2", [](const StereoCalibration& c) { return rect(c.roi2); })
      .def_readonly("format", &StereoCalibration::format,
                    "Where it came from: 'horopter' (calibrate), or the imported format: "
                    "'opencv', 'opencv stereo_calib', 'ros camera_info'")
      .def_property_readonly(
          "inner_corners",
          [](const StereoCalibration& c) -> py::object {
            if (c.board.innerCorners.area() == 0) return py::none();
            return py::make_tuple(c.board.innerCorners.width, c.board.innerCorners.height);
          },
          "The board's inner corners (per row, per column); None for an imported calibration")
      .def_property_readonly(
          "square_size",
          [](const StereoCalibration& c) -> py::object {
            if (!(c.board.squareSize > 0)) return py::none();
            return py::float_(c.board.squareSize);
          },
          "The board's square size (the unit of every length); None for an imported "
          "calibration")
      .def_readonly("alpha", &StereoCalibration::alpha)
      .def_readonly("rms", &StereoCalibration::rms)
      .def_readonly("rms_left", &StereoCalibration::rmsLeft)
      .def_readonly("rms_right", &StereoCalibration::rmsRight)
      .def_readonly("epipolar_error", &StereoCalibration::epipolarError)
      .def_readonly("homography_error", &StereoCalibration::homographyError)
      .def_readonly("skipped", &StereoCalibration::skipped)
      .def_property_readonly("views", [](const StereoCalibration& c) {
        py::list out;
        for (const ViewError& v : c.views) {
          py::dict d;
          d["name"] = v.name;
          d["left"] = v.left;
          d["right"] = v.right;
          out.append(d);
        }
        return out;
      });

  m.def("find_board_corners", &findCorners, py::arg("image"),
        py::arg("inner_corners") = py::make_tuple(9, 6),
        "The chessboard's inner corners in an image (grey or BGR uint8), refined to sub-pixel "
        "accuracy, as an (N, 2) float32 array in OpenCV's row-major order; None when the "
        "whole board is not found");
  m.def("calibrate", &calibrate, py::arg("lefts"), py::arg("rights"), py::arg("square_size"),
        py::arg("inner_corners") = py::make_tuple(9, 6), py::arg("min_views") = 5,
        py::arg("alpha") = 0.0,
        "A StereoCalibration from pairs of chessboard views (lists of images, pair i = "
        "lefts[i], rights[i]); square_size sets the unit of every length (metres give "
        "metres). Pairs where the board is not found in both images are skipped and named "
        "in .skipped; fewer than min_views usable pairs is a horopter.Error");
  m.def("load_calibration", &loadCalibration, py::arg("path"), py::arg("right") = py::none(),
        py::arg("image_size") = py::none(), py::arg("alpha") = 0.0,
        "Reads a stereo calibration, its format recognised by content: Horopter's file (as "
        "`horopter calibrate` writes it); an OpenCV FileStorage file with K1 (or M1), D1, K2, "
        "D2, R, T and the image size, with or without R1, R2, P1, P2, Q; OpenCV's stereo_calib "
        "sample pair intrinsics.yml + extrinsics.yml; a ROS camera_info pair (left and right "
        "YAML). path may be a folder holding left.yaml + right.yaml or intrinsics.yml + "
        "extrinsics.yml. right: the pair's second file where it is not found by name "
        "(left -> right, intrinsics -> extrinsics). image_size: (width, height) for files "
        "without one (must agree with files that have one). alpha: stereoRectify's scaling "
        "where the file has no rectification (0 = only valid pixels, 1 = all pixels). "
        "A bad or incomplete file is a horopter.Error naming the file and the field");
  m.def("save_calibration", &saveStereoCalibration, py::arg("calibration"), py::arg("path"),
        "Writes the calibration in Horopter's format (OpenCV YAML or XML by the extension)");
  m.def("write_ros_camera_info", &writeRosCameraInfo, py::arg("calibration"), py::arg("left_path"),
        py::arg("right_path"), py::arg("camera_name") = "stereo",
        "Writes one ROS camera_info YAML file per camera, as ROS's camera_calibration writes "
        "them (camera_name CAMERA_NAME/left and /right; plumb_bob or rational_polynomial "
        "distortion), every number exact; load_calibration reads the pair back");
  m.def("rectified_geometry", &rectifiedGeometry, py::arg("calibration"),
        "The RectifiedGeometry of a calibration (f, cx, cy from P1; baseline from P2)");

  py::class_<Rectifier>(m, "StereoRectifier",
                        "Undistort-rectify maps computed once; rectify() remaps a captured pair")
      .def(py::init<const StereoCalibration&>(), py::arg("calibration"))
      .def("rectify", &Rectifier::rectify, py::arg("left"), py::arg("right"),
           "(left, right) rectified, as new arrays")
      .def_property_readonly("image_size", &Rectifier::imageSize);
}

}  // namespace horopter::python
