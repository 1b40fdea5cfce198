// `horopter run`: the whole pipeline on a source (the synthetic scene by
// default), with an annotated video, stills and a summary in out/.
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <opencv2/highgui.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>
#include <thread>

#include "commands.hpp"
#include "horopter/calibration.hpp"
#include "horopter/capture.hpp"
#include "horopter/detection.hpp"
#include "horopter/error.hpp"
#include "horopter/geometry.hpp"
#include "horopter/hardware/sim_robot.hpp"
#include "horopter/head_control.hpp"
#include "horopter/movement.hpp"
#include "horopter/movement_training.hpp"
#include "horopter/robot_stage.hpp"
#include "horopter/tracking.hpp"
#include "horopter/tracking_eval.hpp"
#include "horopter/vision_stages.hpp"
#include "run_annotation.hpp"

namespace horopter::cli {

namespace {

std::atomic<bool> gInterrupted{false};

extern "C" void onInterrupt(int) {
  gInterrupted.store(true);
}

const char* kRunHelp =
    "Usage: horopter run [options]\n\n"
    "Runs the frame pipeline (capture -> rectify -> disparity -> mask -> detection ->\n"
    "tracking -> head control -> movement -> robot -> annotate) with several frames in\n"
    "flight, and writes to the\n"
    "output folder: run.avi (annotated video: left image with the zone's ROI, faces, hand\n"
    "candidates, the godfather's tracks and body triangle; disparity colour map; the image\n"
    "inside the horopter; a panel with the godfather's state, the head command, the\n"
    "movement's posterior, decision and action, and with --robot the robot's telemetry),\n"
    "still_*.png and summary.json (and telemetry.jsonl with --robot). With no options: 300\n"
    "frames of the built-in synthetic scene. Ctrl-C stops capture and finishes the frames\n"
    "in flight; with --robot it first latches the base's emergency stop.\n\n"
    "Source:\n"
    "  --source S         synthetic (default), dir:PATH, video:LEFT,RIGHT,\n"
    "                     camera:/dev/videoA,/dev/videoB, sbs:/dev/videoN (side by side)\n"
    "  --frames N         stop after N frames (synthetic default 300; others: the whole input)\n"
    "  --seed S           the synthetic scene's seed (default 1)\n"
    "  --size WxH         synthetic scene or camera size (default 640x480 / driver's)\n"
    "  --fps F            camera rate (default the driver's)\n"
    "  --max-skew-ms T    two cameras: most time between paired frames (default 15)\n"
    "Rectification and zone (sources other than synthetic, which knows its rig):\n"
    "  --calib FILE            rectify with this calibration (horopter calibrate); the zone\n"
    "                          then comes from its geometry and --fixation\n"
    "  --fixation M            with --calib: fixation distance straight ahead, in the\n"
    "                          calibration's unit (default 1.5)\n"
    "  --fixation-disparity D  without --calib (the source is rectified already): disparity\n"
    "                          (px) of the fixation point on the centre column (default: the\n"
    "                          middle of the search range)\n"
    "  --focal-px F            without --calib: focal length (default: image width)\n"
    "Detection, tracking, head control:\n"
    "  --detect SCOPE     region (inside the horopter, default), full (the whole image) or off\n"
    "  --elect-s T        seconds inside the zone to become the godfather (default 2)\n"
    "  --release-s T      seconds outside the zone to be released (default 1)\n"
    "  --head-formula F   atan2 (3-D head point, default) or paper (tan = u / (d lambda f))\n"
    "  --no-head-control  synthetic scene: the head stays still (default: closed loop, a\n"
    "                     command from frame N acts at frame N + 3)\n"
    "Movement and robot:\n"
    "  --model FILE       movement model (horopter train; default: the default model, trained\n"
    "                     in-process in a few seconds)\n"
    "  --no-movement      no movement analysis (LMA, classifier, behaviour)\n"
    "  --robot R          none (default) or sim: the real DYNAMIXEL head and Segway RMP\n"
    "                     drivers on simulated devices (a pty and an in-process CAN bus)\n"
    "                     receive the head commands and the movement's base velocities;\n"
    "                     out/telemetry.jsonl logs commands, measured angles and odometry\n"
    "Scheduling:\n"
    "  --backend B        scalar, avx2, opencl..., auto (default auto)\n"
    "  --threads N        threads of the front end's pool (default: all cores with one frame\n"
    "                     in flight, all but one with more)\n"
    "  --in-flight K      frames in flight, 1..64 (default 3); offline, a frame counts from\n"
    "                     the start of its capture (1: one frame at a time; 3: frame N + 2\n"
    "                     is captured while N + 1 and N are in the stages; with more than\n"
    "                     one, the synthetic scene renders on the capture thread alone)\n"
    "  --live             live mode: capture never waits, stale frames are dropped\n"
    "                     (default for cameras; offline, every frame in order, otherwise)\n"
    "  --until STAGE      run only up to rectify, disparity or mask (for profiling; no\n"
    "                     annotation or video)\n"
    "Output:\n"
    "  -o, --out DIR      output folder (default out)\n"
    "  --trace FILE       Chrome trace events (open in Perfetto or chrome://tracing)\n"
    "  --json             print the summary as one JSON object on stdout\n"
    "  --display          show the annotated frames in a window (needs a display)\n"
    "  --no-video         do not write run.avi\n\n";

struct RunJob {
  std::string source = "synthetic";
  CaptureOptions capture;
  bool framesGiven = false;
  int frames = 300;
  StereoParams stereo;
  MedianParams median;
  std::string backend = "auto";
  int threads = 1;
  int inFlight = 3;
  bool live = false, liveGiven = false;
  std::string until;
  std::string outDir = "out";
  std::string trace;
  bool json = false, display = false, video = true;
  std::optional<double> fixationDisparity, focalPx;
  std::string calib;
  double fixationDistance = 1.5;
  std::string detect = "region";
  ElectionOptions election;
  std::string headFormula = "atan2";
  bool headControl = true;
  std::string model;
  bool movement = true;
  std::string robot = "none";
};

void parseSize(const std::string& text, int& width, int& height) {
  if (std::sscanf(text.c_str(), "%dx%d", &width, &height) != 2 || width < 16 || height < 16 ||
      width > 16384 || height > 16384)
    throw Error("--size must be WxH with both between 16 and 16384, got '" + text + "'");
}

RunJob parseRun(Args& args) {
  RunJob job;
  job.source = args.stringValue("--source", job.source);
  if (auto frames = args.value("--frames")) {
    job.frames = std::stoi(*frames);
    if (job.frames < 1) throw Error("--frames must be >= 1, got " + *frames);
    job.framesGiven = true;
  }
  job.capture.scene.seed = static_cast<std::uint64_t>(args.intValue("--seed", 1));
  if (auto size = args.value("--size")) {
    parseSize(*size, job.capture.width, job.capture.height);
    job.capture.scene.width = job.capture.width;
    job.capture.scene.height = job.capture.height;
  }
  job.capture.fps = args.doubleValue("--fps", 0);
  job.capture.maxSkewMs = args.doubleValue("--max-skew-ms", job.capture.maxSkewMs);
  job.stereo = parseStereoFlags(args, job.stereo);
  job.median = parseMedianFlags(args, job.median);
  job.backend = args.stringValue("--backend", job.backend);
  job.inFlight = args.intValue("--in-flight", job.inFlight);
  // With frames in flight, capture and the other stages keep a core busy
  // with the neighbouring frames, so the front end's pool takes the other
  // cores (a pool as wide as the machine would share a core with them and
  // wait on its slowest stripe). On 2 cores, `--until mask --in-flight 3`:
  // 184-214 frames/s with one thread against 162-202 with two.
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  job.threads = parseThreads(args, job.inFlight > 1 ? std::max(1, cores - 1) : cores);
  job.liveGiven = job.live = args.flag("--live");
  job.until = args.stringValue("--until", "");
  if (!job.until.empty() && job.until != "rectify" && job.until != "disparity" &&
      job.until != "mask")
    throw Error("--until takes rectify, disparity or mask, got '" + job.until + "'");
  job.outDir = args.stringValue("-o", args.stringValue("--out", job.outDir));
  job.trace = args.stringValue("--trace", "");
  job.json = args.flag("--json");
  job.display = args.flag("--display");
  job.video = !args.flag("--no-video");
  job.fixationDisparity = args.optionalDouble("--fixation-disparity");
  job.focalPx = args.optionalDouble("--focal-px");
  job.calib = args.stringValue("--calib", "");
  job.fixationDistance = args.doubleValue("--fixation", job.fixationDistance);
  job.detect = args.stringValue("--detect", job.detect);
  if (job.detect != "region" && job.detect != "full" && job.detect != "off")
    throw Error("--detect takes region, full or off, got '" + job.detect + "'");
  job.election.electS = args.doubleValue("--elect-s", job.election.electS);
  job.election.releaseS = args.doubleValue("--release-s", job.election.releaseS);
  job.headFormula = args.stringValue("--head-formula", job.headFormula);
  if (job.headFormula != "atan2" && job.headFormula != "paper")
    throw Error("--head-formula takes atan2 or paper, got '" + job.headFormula + "'");
  job.headControl = !args.flag("--no-head-control");
  job.model = args.stringValue("--model", "");
  job.movement = !args.flag("--no-movement");
  job.robot = args.stringValue("--robot", job.robot);
  if (job.robot != "none" && job.robot != "sim")
    throw Error("--robot takes none or sim, got '" + job.robot +
                "' (real robots: horopter head / horopter base)");
  if (!(job.fixationDistance > 0 && std::isfinite(job.fixationDistance)))
    throw Error("--fixation must be a positive distance");
  for (const auto& v : {job.fixationDisparity, job.focalPx})
    if (v && !(*v > 0 && std::isfinite(*v)))
      throw Error("--fixation-disparity and --focal-px must be positive numbers");
  args.finish("run");
  const bool camera = job.source.rfind("camera:", 0) == 0 || job.source.rfind("sbs:", 0) == 0;
  if (camera && !job.liveGiven) job.live = true;
  job.capture.frames = job.frames;
  // With frames in flight the other cores work on the frames ahead, so the
  // synthetic scene renders on the capture thread alone rather than adding
  // OpenCV's threads beside the front end's pool (oversubscribed cores).
  if (job.inFlight > 1) job.capture.scene.threads = 1;
  // A run scores nothing against the truth's per-pixel maps (its view shows
  // the head pose and the people's truth only): they are not computed.
  job.capture.scene.pixelTruth = false;
  return job;
}

// Rectification and thresholds from a calibration file: maps computed once,
// the zone from the rectified geometry and a fixation straight ahead.
std::pair<RectifyFunction, ThresholdFunction> calibrated(const RunJob& job) {
  const StereoCalibration calibration = loadStereoCalibration(job.calib);
  auto rectifier = std::make_shared<StereoRectifier>(calibration);
  RectifyFunction rectify = [rectifier](const cv::Mat& l, const cv::Mat& r, cv::Mat& lo,
                                        cv::Mat& ro) {
    rectifier->rectify(l, r);
    lo = rectifier->left().clone();  // the rectifier reuses its buffers
    ro = rectifier->right().clone();
  };
  const RectifiedGeometry g = rectifiedGeometry(calibration);
  const ViethMuellerCircle circle =
      viethMuellerCircle(g.baseline, fixationAtDistance(g.baseline, job.fixationDistance));
  ThresholdFunction thresholds = [g, circle](const Frame&, std::vector<std::int16_t>& out) {
    horopterThresholds(g, circle, out);
  };
  return {rectify, thresholds};
}

// Annotates, shows and writes each finished frame; draws the progress bar.
class Output {
 public:
  Output(const RunJob& job, std::int64_t expected) : job_(job), expected_(expected) {
    std::filesystem::create_directories(job.outDir);
    tty_ = isatty(STDERR_FILENO) && !job.json;
    start_ = SteadyClock::now();
  }
  ~Output() {
    if (tty_ && shown_) std::cerr << "\n";
  }

  // Writes the last frame's still when the source's length was not known.
  void finish() {
    if (!lastView_.empty()) writeStill(lastView_, lastIndex_);
  }

  void operator()(const Frame& f) {
    ++done_;
    const double seconds = std::chrono::duration<double>(SteadyClock::now() - start_).count();
    const double fps = seconds > 0 ? static_cast<double>(done_) / seconds : 0;
    const bool still = f.index == 0 || f.index == expected_ / 2 || f.index + 1 == expected_;
    // Drawing a view costs a few ms of CPU (text above all): only for the
    // video, the window, the stills, and the last frame when the length is
    // not known.
    if (job_.until.empty() && (job_.video || job_.display || still || expected_ <= 0)) {
      const cv::Mat view = annotateFrame(f, job_.stereo, fps);
      if (job_.video) writeVideo(view);
      if (still) {
        writeStill(view, f.index);
      } else {
        lastView_ = view;  // the last frame's still, once the run ends
        lastIndex_ = f.index;
      }
      if (job_.display) {
        cv::imshow("horopter", view);
        if (cv::waitKey(1) == 27) gInterrupted = true;  // Esc stops like Ctrl-C
      }
    }
    if (tty_ && (done_ % 5 == 0 || done_ == expected_)) progress(fps);
  }

 private:
  void writeStill(const cv::Mat& view, std::int64_t index) {
    const std::string path = job_.outDir + "/still_" + std::to_string(index) + ".png";
    if (!cv::imwrite(path, view)) throw Error("cannot write '" + path + "'");
    lastView_.release();
  }

  void writeVideo(const cv::Mat& view) {
    if (!writer_.isOpened()) {
      const std::string path = job_.outDir + "/run.avi";
      if (!writer_.open(path, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 30, view.size()))
        throw Error("cannot write the video '" + path + "' (no MJPG encoder in this OpenCV?)");
    }
    writer_.write(view);
  }

  void progress(double fps) {
    shown_ = true;
    constexpr int kWidth = 30;
    if (expected_ > 0) {
      const int filled =
          static_cast<int>(kWidth * std::min<std::int64_t>(done_, expected_) / expected_);
      std::fprintf(stderr, "\r[%s%s] %lld/%lld frames, %.0f frames/s ",
                   std::string(filled, '#').c_str(), std::string(kWidth - filled, '.').c_str(),
                   static_cast<long long>(done_), static_cast<long long>(expected_), fps);
    } else {
      std::fprintf(stderr, "\r%lld frames, %.0f frames/s ", static_cast<long long>(done_), fps);
    }
  }

  const RunJob& job_;
  std::int64_t expected_, done_ = 0;
  bool tty_ = false, shown_ = false;
  SteadyClock::time_point start_;
  cv::VideoWriter writer_;
  cv::Mat lastView_;
  std::int64_t lastIndex_ = 0;
};

void printSummary(const RunSummary& s, const RunJob& job, const std::string& backendName) {
  std::printf("%lld frames in %.2f s: %.1f frames/s end to end, latency %.1f ms (max %.1f)",
              static_cast<long long>(s.completed), s.seconds, s.fps(), s.meanLatencyMs,
              s.maxLatencyMs);
  if (s.dropped > 0) std::printf(", %lld stale frames dropped", static_cast<long long>(s.dropped));
  std::printf("\n%d frame(s) in flight, %s mode, backend %s, %d thread(s)%s\n", job.inFlight,
              job.live ? "live" : "offline", backendName.c_str(), job.threads,
              s.stoppedByRequest ? ", stopped by request" : "");
  std::printf("%-28s %8s %10s\n", "stage", "ms/frame", "frames/s");
  for (const auto& st : s.stages)
    std::printf("%-28s %8.2f %10.1f\n", st.name.c_str(), st.meanMs, st.fps());
}

}  // namespace

int runPipeline(Args& args) {
  if (args.flag("--help") || args.flag("-h")) {
    std::cout << kRunHelp << stereoFlagsHelp(StereoParams{}, MedianParams{});
    return 0;
  }
  const RunJob job = parseRun(args);
  if (job.display && !std::getenv("DISPLAY") && !std::getenv("WAYLAND_DISPLAY"))
    throw Error("--display needs a display (DISPLAY is not set): drop --display, or run under X");

  const Backend& backend = findBackend(job.backend);
  const bool detect = job.detect != "off" && job.until.empty();
  // The synthetic scene closed loop: the view turns with the head commands.
  const bool closedLoop =
      detect && job.headControl && !job.live && job.calib.empty() && job.source == "synthetic";
  std::unique_ptr<FrameSource> source;
  ClosedLoopSyntheticSource* loop = nullptr;
  if (closedLoop) {
    auto s = std::make_unique<ClosedLoopSyntheticSource>(job.capture.scene, job.capture.frames);
    loop = s.get();
    source = std::move(s);
  } else {
    source = openSource(job.source, job.capture);
  }
  ThresholdFunction thresholds;
  RectifyFunction rectify;
  TrackerOptions tracker;
  tracker.election = job.election;
  tracker.captureTime = job.live;
  tracker.maxDisparityPx = job.stereo.minDisparity + job.stereo.numDisparities - 1;
  if (!job.calib.empty()) {
    std::tie(rectify, thresholds) = calibrated(job);
    tracker.rig = rectifiedGeometry(loadStereoCalibration(job.calib));
  } else if (auto* synthetic = dynamic_cast<SyntheticSource*>(source.get())) {
    thresholds = syntheticZoneThresholds(synthetic->scene());
  } else if (loop) {
    thresholds = syntheticZoneThresholds(loop->scene());
  } else {
    thresholds = fixationDisparityThresholds(job.stereo, job.fixationDisparity, job.focalPx);
  }
  const synth::SyntheticScene* scene = loop ? &loop->scene() : nullptr;
  if (auto* synthetic = dynamic_cast<SyntheticSource*>(source.get())) scene = &synthetic->scene();
  if (scene) {
    tracker.rig = RectifiedGeometry{scene->focalPx(), scene->cx(), scene->baselineM(), scene->cy()};
    tracker.framesPerSecond = scene->options().framesPerSecond;
  }

  PipelineOptions options;
  options.mode = job.live ? PipelineMode::Live : PipelineMode::Offline;
  options.inFlight = job.inFlight;
  options.maxFrames = job.framesGiven ? job.frames : -1;
  options.stopRequested = &gInterrupted;
  const std::int64_t expected =
      job.framesGiven ? job.frames : (job.source == "synthetic" ? job.capture.frames : -1);
  Output output(job, expected);
  options.onFrame = [&output](const Frame& f) { output(f); };

  Pipeline pipeline(options);
  pipeline.add(makeRectifyStage(rectify));
  if (job.until != "rectify") {
    pipeline.add(makeDisparityStage(job.stereo, job.median, backend, job.threads));
    if (job.until != "disparity") pipeline.add(makeMaskStage(thresholds, job.stereo, backend));
  }
  if (detect) {
    DetectorOptions detector;
    detector.scope =
        job.detect == "full" ? DetectionScope::FullImage : DetectionScope::HoropterRegion;
    pipeline.add(makeDetectionStage(detector));
    if (loop) tracker.capturePose = syntheticCapturePose();
    pipeline.add(makeTrackingStage(tracker));
    if (loop) {
      HeadControlOptions head;
      head.formula = job.headFormula == "paper" ? PanTiltFormula::Paper : PanTiltFormula::Atan2;
      pipeline.add(makeSyntheticHeadControlStage(head, *loop));
    }
    if (job.movement) {
      if (!job.json)
        std::cerr << "horopter run: movement model "
                  << (job.model.empty() ? "(default)" : job.model) << "\n";
      pipeline.add(makeMovementStage(loadOrTrainMovementModel(job.model)));
    }
  }
  // The simulated robot: commands go through the real drivers; Ctrl-C latches
  // the base's emergency stop at once (the robot stage checks it every frame).
  std::unique_ptr<hw::SimulatedRobot> robot;
  std::unique_ptr<hw::TelemetryLog> telemetry;
  if (job.robot == "sim") {
    if (!detect)
      throw Error("--robot sim needs detection and tracking: drop --detect off / --until");
    robot = std::make_unique<hw::SimulatedRobot>();
    std::filesystem::create_directories(job.outDir);
    telemetry = std::make_unique<hw::TelemetryLog>(job.outDir + "/telemetry.jsonl");
    RobotStageOptions r;
    r.head = &robot->head();
    r.base = &robot->base();
    r.telemetrySource = robot.get();
    r.log = telemetry.get();
    r.emergencyStop = &gInterrupted;
    pipeline.add(makeRobotStage(r));
  }
  if (!job.json)
    std::cerr << "horopter run: source " << source->name() << ", backend " << backend.name << ", "
              << job.threads << " thread(s), " << job.inFlight << " frame(s) in flight\n";

  gInterrupted = false;
  const auto previous = std::signal(SIGINT, onInterrupt);
  RunSummary summary;
  try {
    summary = pipeline.run(*source);
  } catch (...) {
    std::signal(SIGINT, previous);
    throw;
  }
  std::signal(SIGINT, previous);
  output.finish();
  if (robot) {
    if (summary.stoppedByRequest) robot->base().emergencyStop();
    const hw::TelemetrySample last = robot->sample();
    robot->shutdown();  // zero velocity, threads joined
    if (!job.json)
      std::printf(
          "robot (simulated): %ld telemetry lines in %s/telemetry.jsonl; odometry x %.2f m, "
          "heading %.0f deg%s\n",
          telemetry->lines(), job.outDir.c_str(), last.odometry ? last.odometry->x : 0.0,
          last.odometry ? last.odometry->heading * 57.29578 : 0.0,
          summary.stoppedByRequest ? "; emergency stop latched" : "");
  }

  const std::string json = summaryJson(summary);
  std::ofstream(job.outDir + "/summary.json") << json << "\n";
  if (!job.trace.empty()) writeChromeTrace(summary, job.trace);
  if (job.json)
    std::printf("%s\n", json.c_str());
  else
    printSummary(summary, job, backend.name);
  return 0;
}

}  // namespace horopter::cli
