// The `horopter` command-line tool.
#include <cstring>
#include <exception>
#include <iostream>
#include <string>

#include "commands.hpp"
#include "display_probe.hpp"
#include "horopter/core/error.hpp"
#include "horopter/version.h"

namespace {

const char* kUsage =
    "Usage: horopter COMMAND [options]   (horopter COMMAND --help for its options)\n"
    "       horopter --version             (or -V: the version, then exit)\n\n"
    "Horopter: a stereo vision engine that keeps only what lies inside the robot's zone\n"
    "of interaction (the Vieth-Mueller circle through both cameras and the fixation point).\n\n"
    "Commands:\n"
    "  run           the frame pipeline on the built-in synthetic scene (or cameras, files)\n"
    "                -> out/ (annotated video, stills, summary)\n"
    "  disparity     disparity, cleanup, median and horopter mask of a rectified pair\n"
    "                (--example: Middlebury's Aloe pair from opencv-doc)\n"
    "  eval-stereo   accuracy against ground truth, cv::StereoBM beside us (--peer opencv)\n"
    "  eval-zone     what zone-limited matching (run --zone-search 1) changes in the zone\n"
    "                mask, against the full range and the true zone\n"
    "  eval-tracking tracker loss, false positives and frames/s on synthetic trials, detection\n"
    "                inside the horopter's region vs over the full image\n"
    "  train         the movement classifier from synthetic labelled sequences -> model file\n"
    "  classify      movement decisions and robot actions for a recorded track or synthetic\n"
    "                sequences\n"
    "  eval-interaction  Table III: tracker loss and movement classification rates on\n"
    "                synthetic trials, full image vs the horopter region, and frames/s\n"
    "  devices       CPU features, backends and OpenCL devices of this machine (--json)\n"
    "  calibrate     stereo calibration from chessboard views -> calib.yml (OpenCV YAML);\n"
    "                --ros-out DIR: also ROS camera_info; --convert IN --to horopter|ros\n"
    "  rectify       rectified pairs side by side with horizontal lines, to check a calibration\n"
    "  geometry      the zone of interaction of a calibrated head for a fixation (+ top-down "
    "PNG)\n"
    "  head          move the pan-tilt(-vergence) head (DYNAMIXEL 2.0 or FLIR PTU, or --sim)\n"
    "                and print the measured angles\n"
    "  base          drive the Segway RMP base (SocketCAN, USB or --sim) and print odometry\n"
    "  profile       per-stage time of the front end on each backend (OpenCL: device time of\n"
    "                upload, each kernel, download)\n\n"
    "Exit status: 0 done; 1 the work failed; 2 a wrong command line (an unknown option, a value\n"
    "out of range, a missing file): every command checks all its options before it starts.\n";

}  // namespace

int main(int argc, char** argv) {
  using namespace horopter::cli;
  if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h") ||
      !std::strcmp(argv[1], "help")) {
    std::cout << kUsage;
    return argc < 2 ? 2 : 0;
  }
  if (!std::strcmp(argv[1], "--version") || !std::strcmp(argv[1], "-V")) {
    if (argc > 2) {
      std::cerr << "horopter: --version takes no arguments\n";
      return 2;
    }
    std::cout << "horopter " << HOROPTER_VERSION_STRING << "\n";
    return 0;
  }
  const std::string command = argv[1];
  Args args(argc, argv, 2);
  try {
    if (command == "run") return runPipeline(args);
    if (command == "disparity") return runDisparity(args);
    if (command == "eval-stereo") return runEvalStereo(args);
    if (command == "eval-tracking") return runEvalTracking(args);
    if (command == "eval-zone") return runEvalZone(args);
    if (command == "train") return runTrain(args);
    if (command == "classify") return runClassify(args);
    if (command == "eval-interaction") return runEvalInteraction(args);
    if (command == "devices") return runDevices(args);
    if (command == "calibrate") return runCalibrate(args);
    if (command == "rectify") return runRectify(args);
    if (command == "geometry") return runGeometry(args);
    if (command == "head") return runHead(args);
    if (command == "base") return runBase(args);
    if (command == "profile") return runProfile(args);
    if (command == kDisplayProbeCommand) return probeDisplay();
    std::cerr << "horopter: unknown command '" << command << "'\n\n" << kUsage;
    return 2;
  } catch (const UsageError& e) {
    std::cerr << "horopter " << command << ": error: " << e.what() << "\n";
    return 2;
  } catch (const horopter::Error& e) {
    std::cerr << "horopter " << command << ": error: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "horopter " << command << ": unexpected error: " << e.what() << "\n";
    return 1;
  }
}
