// Horopter's front end inside the OpenCV capture loop a robot already has:
// two cv::VideoCapture in, the disparity and the horopter mask of each frame
// out, no window (cv::imshow is the caller's to add).
//
//   opencv_loop LEFT RIGHT [--frames N] [--num-disparities N]
//               [--fixation-disparity PX] [--backend NAME] [-o DIR]
//
// LEFT and RIGHT are whatever cv::VideoCapture opens: two video files, two
// image sequences ("views/left%02d.jpg"), or two camera indices ("0" "2").
// The pair is taken as rectified (rectify it first with horopter::Rectifier
// and a calibration file when it is not). With -o, each frame's mask is
// written as DIR/mask_NNN.png (255 inside the zone of interaction).
#include <horopter/vision/frontend.hpp>
#include <horopter/vision/geometry.hpp>
#include <horopter/vision/opencv.hpp>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <string>
#include <vector>

namespace {

// A camera index ("0") opens the device, anything else a file or sequence.
bool openCapture(cv::VideoCapture& capture, const std::string& what) {
  const bool index = !what.empty() && what.find_first_not_of("0123456789") == std::string::npos;
  return index ? capture.open(std::atoi(what.c_str())) : capture.open(what);
}

int usage() {
  std::fprintf(stderr,
               "usage: opencv_loop LEFT RIGHT [--frames N] [--num-disparities N] "
               "[--fixation-disparity PX] [--backend NAME] [-o DIR]\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> inputs;
  int frames = 0;  // 0: until either capture ends
  int numDisparities = 64;
  double fixationPx = 0;  // 0: the middle of the search range
  std::string backend = "auto", outDir;
  for (int i = 1; i < argc; ++i) {
    const bool hasValue = i + 1 < argc;
    if (std::strcmp(argv[i], "--frames") == 0 && hasValue) {
      frames = std::atoi(argv[++i]);
    } else if (std::strcmp(argv[i], "--num-disparities") == 0 && hasValue) {
      numDisparities = std::atoi(argv[++i]);
    } else if (std::strcmp(argv[i], "--fixation-disparity") == 0 && hasValue) {
      fixationPx = std::atof(argv[++i]);
    } else if (std::strcmp(argv[i], "--backend") == 0 && hasValue) {
      backend = argv[++i];
    } else if (std::strcmp(argv[i], "-o") == 0 && hasValue) {
      outDir = argv[++i];
    } else if (argv[i][0] == '-') {
      return usage();
    } else {
      inputs.emplace_back(argv[i]);
    }
  }
  if (inputs.size() != 2 || frames < 0) return usage();

  cv::VideoCapture leftCapture, rightCapture;
  if (!openCapture(leftCapture, inputs[0]) || !openCapture(rightCapture, inputs[1])) {
    std::fprintf(stderr, "opencv_loop: cannot open %s and %s with cv::VideoCapture\n",
                 inputs[0].c_str(), inputs[1].c_str());
    return 1;
  }
  if (!outDir.empty()) std::filesystem::create_directories(outDir);
  try {
    // Built once, reused every frame: its buffers stay allocated.
    horopter::StereoParams stereo;
    stereo.numDisparities = numDisparities;
    horopter::StereoFrontend frontend(stereo, horopter::MedianParams{},
                                      horopter::findBackend(backend));
    std::vector<std::int16_t> thresholds;
    cv::Mat leftColour, rightColour, left, right;
    int done = 0;
    while (frames == 0 || done < frames) {
      if (!leftCapture.read(leftColour) || !rightCapture.read(rightColour)) break;
      cv::cvtColor(leftColour, left, cv::COLOR_BGR2GRAY);
      cv::cvtColor(rightColour, right, cv::COLOR_BGR2GRAY);
      if (thresholds.size() != static_cast<std::size_t>(left.cols)) {
        // The zone: the Vieth-Mueller circle through both cameras and the
        // fixation straight ahead (focal length: the image width).
        const horopter::RectifiedGeometry geometry{
            static_cast<double>(left.cols), (left.cols - 1) / 2.0, 1.0, (left.rows - 1) / 2.0};
        const double px = fixationPx > 0 ? fixationPx : stereo.numDisparities / 2.0;
        thresholds = horopter::horopterThresholds(
            geometry, left.cols, horopter::fixationFromDisparity(geometry, geometry.cx, px));
      }
      frontend.computeDisparity(horopter::viewOf(left), horopter::viewOf(right));
      frontend.computeMask(thresholds, horopter::viewOf(leftColour));
      const cv::Mat mask = horopter::matOf(frontend.mask());  // a view: no copy
      const double inside = 100.0 * cv::countNonZero(mask) / static_cast<double>(mask.total());
      std::printf("frame %d: %dx%d, %.1f%% inside the zone\n", done, left.cols, left.rows, inside);
      if (!outDir.empty()) {
        char name[32];
        std::snprintf(name, sizeof name, "mask_%03d.png", done);
        const std::string path = (std::filesystem::path(outDir) / name).string();
        if (!cv::imwrite(path, mask)) {
          std::fprintf(stderr, "opencv_loop: cannot write %s\n", path.c_str());
          return 1;
        }
      }
      ++done;
    }
    std::printf("%d frames, backend %s\n", done, frontend.backend().name.c_str());
    return done > 0 ? 0 : 1;
  } catch (const std::exception& e) {  // horopter::Error says what to fix
    std::fprintf(stderr, "opencv_loop: %s\n", e.what());
    return 1;
  }
}
