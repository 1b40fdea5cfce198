// Embedding the C++ API as a robot would: a rectified stereo pair through the
// front end (disparity) and the horopter mask of a fixation, then the whole
// pipeline (detection and tracking included) over a folder of pairs.
//
//   embed [--left L --right R] [--frames N] [--backend NAME]
// (default pair: OpenCV's aloe, from Debian's opencv-doc)
#include <horopter/app/pipeline_builder.hpp>
#include <horopter/vision/frontend.hpp>
#include <horopter/vision/geometry.hpp>
#include <horopter/vision/opencv.hpp>

#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>

int main(int argc, char** argv) {
  std::string leftPath = "/usr/share/doc/opencv-doc/examples/data/aloeL.jpg";
  std::string rightPath = "/usr/share/doc/opencv-doc/examples/data/aloeR.jpg";
  int frames = 2;
  std::string backend = "auto";
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--left") == 0 && i + 1 < argc) {
      leftPath = argv[++i];
    } else if (std::strcmp(argv[i], "--right") == 0 && i + 1 < argc) {
      rightPath = argv[++i];
    } else if (std::strcmp(argv[i], "--frames") == 0 && i + 1 < argc) {
      frames = std::atoi(argv[++i]);
    } else if (std::strcmp(argv[i], "--backend") == 0 && i + 1 < argc) {
      backend = argv[++i];
    } else {
      std::fprintf(stderr, "usage: embed [--left L --right R] [--frames N] [--backend NAME]\n");
      return 2;
    }
  }
  try {
    const cv::Mat leftColour = cv::imread(leftPath), rightColour = cv::imread(rightPath);
    if (leftColour.empty() || rightColour.empty()) {
      std::fprintf(stderr, "embed: cannot read %s and %s (install opencv-doc, or give a pair)\n",
                   leftPath.c_str(), rightPath.c_str());
      return 1;
    }
    cv::Mat left, right;
    cv::cvtColor(leftColour, left, cv::COLOR_BGR2GRAY);
    cv::cvtColor(rightColour, right, cv::COLOR_BGR2GRAY);

    // The front end: cv::StereoBM's names, a backend chosen at run time.
    horopter::StereoParams stereo;
    stereo.numDisparities = 64;
    horopter::StereoFrontend frontend(stereo, horopter::MedianParams{},
                                      horopter::findBackend(backend));
    frontend.computeDisparity(horopter::viewOf(left), horopter::viewOf(right));

    // The zone: the Vieth-Mueller circle through both cameras and a fixation
    // 32 px of disparity straight ahead (focal length: the image width).
    const horopter::RectifiedGeometry geometry{static_cast<double>(left.cols),
                                               (left.cols - 1) / 2.0, 1.0, (left.rows - 1) / 2.0};
    const std::vector<std::int16_t> thresholds = horopter::horopterThresholds(
        geometry, left.cols, horopter::fixationFromDisparity(geometry, geometry.cx, 32.0));
    frontend.computeMask(thresholds, horopter::viewOf(leftColour));
    const cv::Mat mask = horopter::matOf(frontend.mask());
    const double inside = 100.0 * cv::countNonZero(mask) / static_cast<double>(mask.total());
    std::printf("%s: %dx%d, %.1f%% inside the zone, backend %s\n", leftPath.c_str(), left.cols,
                left.rows, inside, frontend.backend().name.c_str());
    if (inside <= 1 || inside >= 99) {
      std::fprintf(stderr, "embed: a zone that holds all or nothing of the pair\n");
      return 1;
    }

    // The whole pipeline over a folder of pairs (a camera would be
    // "camera:/dev/video0,/dev/video2"), as `horopter run` assembles it.
    const std::filesystem::path folder =
        std::filesystem::temp_directory_path() / "horopter_embed_pairs";
    std::filesystem::create_directories(folder);
    for (int i = 0; i < frames; ++i) {
      const std::string n = std::to_string(i);
      if (!cv::imwrite((folder / ("left_" + n + ".png")).string(), leftColour) ||
          !cv::imwrite((folder / ("right_" + n + ".png")).string(), rightColour)) {
        std::fprintf(stderr, "embed: cannot write the pairs to %s\n", folder.c_str());
        return 1;
      }
    }
    horopter::PipelineConfig config;
    config.source = "dir:" + folder.string();
    config.backend = backend;
    config.stereo = stereo;
    config.zone.fixationDisparityPx = 32.0;
    horopter::PipelineHooks hooks;
    int seen = 0;
    hooks.onFrame = [&seen](const horopter::Frame& f) {
      ++seen;
      std::printf("frame %lld: godfather %s\n", static_cast<long long>(f.index),
                  f.body.godfather ? "elected" : "none yet");
    };
    horopter::AssembledPipeline pipeline = horopter::buildPipeline(config, std::move(hooks));
    const horopter::RunSummary summary = pipeline.run();
    std::filesystem::remove_all(folder);
    std::printf("%lld frames through the pipeline\n", static_cast<long long>(summary.completed));
    return seen == frames ? 0 : 1;
  } catch (const std::exception& e) {  // horopter::Error says what to fix
    std::fprintf(stderr, "embed: %s\n", e.what());
    return 1;
  }
}
