// Embedding the C++ API: frames of the built-in synthetic scene through the
// stereo front end and the horopter mask, compared with the scene's truth.
//
//   embed [--frames N] [--start I] [--backend NAME]
// (from frame 60 on, the main person stands inside the zone)
#include <horopter/frontend.hpp>
#include <horopter/geometry.hpp>
#include <horopter/opencv.hpp>
#include <horopter/synthetic_scene.hpp>

#include <cstdio>
#include <cstring>
#include <exception>
#include <opencv2/imgproc.hpp>
#include <string>

int main(int argc, char** argv) {
  int frames = 3;
  int start = 60;
  std::string backend = "auto";
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--frames") == 0 && i + 1 < argc) {
      frames = std::atoi(argv[++i]);
    } else if (std::strcmp(argv[i], "--start") == 0 && i + 1 < argc) {
      start = std::atoi(argv[++i]);
    } else if (std::strcmp(argv[i], "--backend") == 0 && i + 1 < argc) {
      backend = argv[++i];
    } else {
      std::fprintf(stderr, "usage: embed [--frames N] [--start I] [--backend NAME]\n");
      return 2;
    }
  }
  try {
    horopter::synth::SceneOptions options;
    options.width = 320;
    options.height = 240;
    horopter::synth::SyntheticScene scene(options);

    horopter::StereoParams stereo;  // cv::StereoBM's names
    stereo.numDisparities = 64;
    horopter::StereoFrontend frontend(stereo, horopter::MedianParams{},
                                      horopter::findBackend(backend));
    const horopter::RectifiedGeometry geometry{scene.focalPx(), scene.cx(), scene.baselineM(),
                                               scene.cy()};
    for (int i = start; i < start + frames; ++i) {
      const horopter::synth::SyntheticFrame frame = scene.render(i);
      cv::Mat left, right;
      cv::cvtColor(frame.left, left, cv::COLOR_BGR2GRAY);
      cv::cvtColor(frame.right, right, cv::COLOR_BGR2GRAY);
      frontend.computeDisparity(horopter::viewOf(left), horopter::viewOf(right));

      // The zone: the circle through both cameras and the head's fixation.
      const auto circle = horopter::viethMuellerCircle(
          geometry.baseline,
          horopter::fixationFromVergence(geometry.baseline, frame.truth.head.vergence));
      std::vector<std::int16_t> thresholds(static_cast<std::size_t>(left.cols));
      horopter::horopterThresholds(geometry, circle, thresholds);
      frontend.computeMask(thresholds, horopter::viewOf(frame.left));

      const cv::Mat mask = horopter::matOf(frontend.mask());
      const int inside = cv::countNonZero(mask);
      const int truthInside = cv::countNonZero(frame.truth.inside);
      const int agree = cv::countNonZero(mask == frame.truth.inside);
      std::printf(
          "frame %d: %.1f%% inside the zone (truth %.1f%%), mask agrees with truth on %.1f%%"
          " of pixels, backend %s\n",
          i, 100.0 * inside / mask.total(), 100.0 * truthInside / mask.total(),
          100.0 * agree / mask.total(), frontend.backend().name.c_str());
      if (agree < 0.8 * static_cast<double>(mask.total())) {
        std::fprintf(stderr, "embed: the mask disagrees with the truth on too many pixels\n");
        return 1;
      }
    }
    return 0;
  } catch (const std::exception& e) {  // horopter::Error says what to fix
    std::fprintf(stderr, "embed: %s\n", e.what());
    return 1;
  }
}
