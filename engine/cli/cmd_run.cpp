// `horopter run`: the whole pipeline on a source (the synthetic scene by
// default), with an annotated video, stills and a summary in out/.
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <opencv2/highgui.hpp>
#include <opencv2/videoio.hpp>
#include <optional>
#include <thread>
#include <vector>

#include "calibration_io.hpp"
#include "command_options.hpp"
#include "commands.hpp"
#include "display_probe.hpp"
#include "file_output.hpp"
#include "horopter/app/pipeline_builder.hpp"
#include "horopter/app/robot_stage.hpp"
#include "horopter/core/error.hpp"
#include "horopter/core/option_table.hpp"
#include "horopter/eval/movement_training.hpp"
#include "horopter/hardware/sim_robot.hpp"
#include "horopter/sim/synthetic_source.hpp"
#include "io/disparity_images.hpp"
#include "json_text.hpp"
#include "option_checks.hpp"
#include "run_annotation.hpp"
#include "shared_options.hpp"
#include "video_recorder.hpp"

namespace horopter::cli {

namespace {

std::atomic<bool> gInterrupted{false};

extern "C" void onInterrupt(int) {
  gInterrupted.store(true);
}

// SIGINT (Ctrl-C), SIGTERM (kill, systemd, docker stop) and SIGHUP (the
// terminal went away) take one path: capture stops, the frames in flight
// finish, the base is stopped and its e-stop latched, the video is closed
// and the summary written. The previous handlers come back on destruction.
class StopSignals {
 public:
  StopSignals() {
    for (std::size_t i = 0; i < std::size(kSignals); ++i)
      previous_[i] = std::signal(kSignals[i], onInterrupt);
  }
  ~StopSignals() {
    for (std::size_t i = 0; i < std::size(kSignals); ++i)
      std::signal(kSignals[i], previous_[i]);
  }
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;

 private:
  static constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP};
  void (*previous_[3])(int) = {};
};

const char* kRunHelpStart =
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
    "in flight; with --robot it first latches the base's emergency stop.\n\n";

constexpr CommandOption kOptions[] = {
    {.kind = OptionKind::Heading, .flag = "Source"},
    {.kind = OptionKind::Text,
     .flag = "--source",
     .value = "S",
     .fallback = "synthetic",
     .help = "synthetic, dir:PATH, video:LEFT,RIGHT, camera:/dev/videoA,/dev/videoB, "
             "sbs:/dev/videoN (side by side)"},
    {.kind = OptionKind::Integer,
     .flag = "--frames",
     .value = "N",
     .min = 1,
     .max = 1000000000,
     .help = "stop after N frames (default: synthetic 300; others the whole input)"},
    {.kind = OptionKind::Integer,
     .flag = "--seed",
     .value = "S",
     .min = 0,
     .max = 1000000000,
     .fallback = "1",
     .help = "the synthetic scene's seed"},
    {.kind = OptionKind::Text,
     .flag = "--size",
     .value = "WxH",
     .help = "synthetic scene or camera size, 16x16..16384x16384 (default 640x480 / the "
             "driver's)"},
    {.kind = OptionKind::Number,
     .flag = "--fps",
     .value = "F",
     .min = 0,
     .max = 1000,
     .unit = "frames/s",
     .fallback = "0",
     .help = "camera rate (0: the driver's)"},
    {.kind = OptionKind::Number,
     .flag = "--max-skew-ms",
     .value = "T",
     .min = 0,
     .max = 10000,
     .unit = "ms",
     .fallbackOf = [] { return defaultText(CaptureOptions{}.maxSkewMs); },
     .help = "two cameras: most time between paired frames"},
    {.kind = OptionKind::Heading,
     .flag = "Rectification and zone (sources other than synthetic, which knows its rig)"},
    {.kind = OptionKind::Text,
     .flag = "--calib",
     .value = "PATH",
     .help = "rectify with this calibration (horopter calibrate's file, OpenCV's, or a ROS "
             "camera_info pair: docs/calibration.md); the zone then comes from its geometry and "
             "--fixation"},
    {.kind = OptionKind::Number,
     .flag = "--fixation",
     .value = "M",
     .min = 1e-6,
     .max = 1e6,
     .fallbackOf = [] { return defaultText(ZoneOptions{}.fixationDistanceM); },
     .help = "with --calib: fixation distance straight ahead, in the calibration's unit"},
    kFixationDisparityOption,
    kFocalPxOption,
    {.kind = OptionKind::Heading, .flag = "Detection, tracking, head control"},
    {.kind = OptionKind::Choice,
     .flag = "--detect",
     .value = "SCOPE",
     .fallback = "region",
     .choices = "region,full,off",
     .help = "where faces and hands are detected: inside the horopter, the whole image, or "
             "nowhere"},
    kHeadFormulaOption,
    {.kind = OptionKind::Switch,
     .flag = "--no-head-control",
     .help = "synthetic scene: the head stays still (default: closed loop, a command from "
             "frame N acts at frame N + 3)"},
    {.kind = OptionKind::Heading, .flag = "Movement and robot"},
    {.kind = OptionKind::Text,
     .flag = "--model",
     .value = "FILE",
     .help = "movement model (horopter train; default: the default model, trained in-process "
             "in a few seconds)"},
    {.kind = OptionKind::Switch,
     .flag = "--no-movement",
     .help = "no movement analysis (LMA, classifier, behaviour)"},
    {.kind = OptionKind::Choice,
     .flag = "--robot",
     .value = "R",
     .fallback = "none",
     .choices = "none,sim",
     .help = "with sim, the real DYNAMIXEL head and Segway RMP drivers on simulated devices (a "
             "pty and an in-process CAN bus) receive the head commands and the movement's base "
             "velocities, and out/telemetry.jsonl logs commands, measured angles and odometry "
             "(real robots: horopter head / horopter base)"},
    {.kind = OptionKind::Heading, .flag = "Scheduling"},
    kBackendOption,
    {.kind = OptionKind::Integer,
     .flag = "--in-flight",
     .value = "K",
     .min = 1,
     .max = 64,
     .fallbackOf =
         [] {
           static const PipelineConfig defaults;
           return defaultText(defaults.inFlight);
         },
     .help = "frames in flight; offline, a frame counts from the start of its capture (1: one "
             "frame at a time; 3: frame N + 2 is captured while N + 1 and N are in the stages; "
             "with more than one, the synthetic scene renders on the capture thread alone)"},
    {.kind = OptionKind::Switch,
     .flag = "--live",
     .help = "live mode: capture never waits, stale frames are dropped (default for cameras; "
             "offline, every frame in order, otherwise)"},
    {.kind = OptionKind::Choice,
     .flag = "--until",
     .value = "STAGE",
     .choices = "rectify,disparity,mask",
     .help = "run only up to this stage (for profiling; no annotation or video)"},
    {.kind = OptionKind::Heading, .flag = "Output"},
    {.kind = OptionKind::Text,
     .flag = "--out",
     .alias = "-o",
     .value = "DIR",
     .fallback = "out",
     .help = "output folder"},
    {.kind = OptionKind::Text,
     .flag = "--trace",
     .value = "FILE",
     .help = "Chrome trace events (open in Perfetto or chrome://tracing)"},
    {.kind = OptionKind::Switch,
     .flag = "--json",
     .help = "print the summary as one JSON object on stdout"},
    {.kind = OptionKind::Switch,
     .flag = "--display",
     .help = "show the annotated frames in a window (needs a display)"},
    {.kind = OptionKind::Switch, .flag = "--no-video", .help = "do not write run.avi"},
    {.kind = OptionKind::Integer,
     .flag = "--video-scale",
     .value = "N",
     .min = 1,
     .max = 8,
     .fallback = "2",
     .help = "run.avi at 1/N of the view's width and height (2: 640x480, a third of the "
             "full size's encoding cost); a frame only the video shows is drawn at that size, "
             "the video is encoded on its own thread, the stills stay full size"},
};

// What `horopter run` does: the pipeline's configuration and the CLI's own
// choices (output, the model file, the simulated robot).
struct RunJob {
  PipelineConfig config;
  sim::SyntheticSourceOptions synthetic;  // the scene for --source synthetic
  bool framesGiven = false;
  int frames = 300;
  bool liveGiven = false;
  std::string until;
  std::string outDir = "out";
  std::string trace;
  bool json = false, display = false, video = true;
  int videoScale = 1;  // the video's width and height are the view's divided by this
  std::string model;
  bool movement = true;
  std::string robot = "none";
};

// Checks a --source spec the way openSource() reads it, before any work:
// the kind, and that the folder, files or devices it names exist.
void checkSource(const std::string& spec) {
  if (spec == "synthetic") return;
  const auto colon = spec.find(':');
  const std::string kind = spec.substr(0, colon);
  const std::string rest = colon == std::string::npos ? "" : spec.substr(colon + 1);
  // "A,B" -> {A, B}.
  const auto twoParts = [&] {
    const auto comma = rest.find(',');
    if (comma == std::string::npos || comma == 0 || comma + 1 == rest.size() ||
        rest.find(',', comma + 1) != std::string::npos)
      throw UsageError("'" + spec + "' needs two comma-separated parts (left,right)");
    return std::vector<std::string>{rest.substr(0, comma), rest.substr(comma + 1)};
  };
  if (kind == "dir" && !rest.empty()) {
    if (!std::filesystem::is_directory(rest))
      throw UsageError("image folder '" + rest + "' does not exist (dir:PATH needs a folder)");
    return;
  }
  if (kind == "video") {
    for (const std::string& f : twoParts())
      requireFile(f, "video file");
    return;
  }
  if (kind == "camera" || (kind == "sbs" && !rest.empty())) {
    for (const std::string& d : kind == "sbs" ? std::vector<std::string>{rest} : twoParts())
      if (!std::filesystem::exists(d))
        throw UsageError("camera '" + d + "' does not exist: list cameras with `ls /dev/video*`");
    return;
  }
  throw UsageError("unknown source '" + spec +
                   "': use synthetic, dir:PATH, video:LEFT,RIGHT, camera:LEFTDEV,RIGHTDEV or "
                   "sbs:DEV");
}

// Every option, checked before the run starts (the model is trained or
// loaded after this, the source opened after that).
RunJob parseRun(Args& args) {
  const CommandOptions o(args, kOptions);
  RunJob job;
  PipelineConfig& c = job.config;
  c.stereo = parseStereoFlags(args, c.stereo);
  c.median = parseMedianFlags(args, c.median);
  c.zoneSearch = parseOptionFlags(args, zoneSearchOptions(), c.zoneSearch);
  c.tracker.election = parseOptionFlags(args, electionOptions(), c.tracker.election);
  c.inFlight = static_cast<int>(o.integer("--in-flight"));
  // With frames in flight, capture and the other stages keep a core busy
  // with the neighbouring frames, so the front end's pool takes the other
  // cores (a pool as wide as the machine would share a core with them and
  // wait on its slowest stripe). On 2 cores, `--until mask --in-flight 3`:
  // 184-214 frames/s with one thread against 162-202 with two.
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  c.threads = parseThreads(args, c.inFlight > 1 ? std::max(1, cores - 1) : cores);
  args.finish("run");

  c.source = o.text("--source");
  if (const auto frames = o.optionalInteger("--frames")) {
    job.frames = static_cast<int>(*frames);
    job.framesGiven = true;
  }
  job.synthetic.scene.seed = static_cast<std::uint64_t>(o.integer("--seed"));
  if (const auto size = o.optionalText("--size")) {
    const ImageSize wh = parseImageSize(*size, "--size", {16, 16}, {16384, 16384});
    c.capture.width = wh.width;
    c.capture.height = wh.height;
    job.synthetic.scene.width = c.capture.width;
    job.synthetic.scene.height = c.capture.height;
  }
  c.capture.fps = o.number("--fps");
  c.capture.maxSkewMs = o.number("--max-skew-ms");
  c.backend = o.text("--backend");
  job.liveGiven = c.live = o.on("--live");
  job.until = o.text("--until");
  if (job.until == "rectify")
    c.stopAfter = StopAfter::Rectify;
  else if (job.until == "disparity")
    c.stopAfter = StopAfter::Disparity;
  else if (job.until == "mask")
    c.stopAfter = StopAfter::Mask;
  job.outDir = o.text("--out");
  job.trace = o.text("--trace");
  job.json = o.on("--json");
  job.display = o.on("--display");
  job.video = !o.on("--no-video");
  job.videoScale = static_cast<int>(o.integer("--video-scale"));
  c.zone.fixationDisparityPx = o.optionalNumber("--fixation-disparity");
  c.zone.focalPx = o.optionalNumber("--focal-px");
  c.zone.calib = o.text("--calib");
  c.zone.fixationDistanceM = o.number("--fixation");
  const std::string detect = o.text("--detect");
  if (detect == "region")
    c.detection = DetectionScope::HoropterRegion;
  else if (detect == "full")
    c.detection = DetectionScope::FullImage;
  else
    c.detection.reset();
  c.head.formula =
      o.text("--head-formula") == "paper" ? PanTiltFormula::Paper : PanTiltFormula::Atan2;
  c.headControl = !o.on("--no-head-control");
  job.model = o.text("--model");
  job.movement = !o.on("--no-movement");
  job.robot = o.text("--robot");

  checkSource(c.source);
  if (!c.zone.calib.empty() && c.source == "synthetic")
    throw UsageError(
        "--calib rectifies a raw camera pair, but the synthetic scene is rectified "
        "already: drop --calib, or give --source");
  if (!c.zone.calib.empty()) asUsageError([&] { requireCalibrationPath(c.zone.calib); });
  if (!job.model.empty()) requireFile(job.model, "movement model");
  requireBackend(c.backend);
  requireWritableFolder(job.outDir, "--out");
  if (!job.trace.empty()) requireWritableFile(job.trace, "--trace");
  if (job.display) checkDisplayOpens();
  if (job.robot == "sim" && !(c.detection && job.until.empty()))
    throw UsageError("--robot sim needs detection and tracking: drop --detect off / --until");

  const bool camera = c.source.rfind("camera:", 0) == 0 || c.source.rfind("sbs:", 0) == 0;
  if (camera && !job.liveGiven) c.live = true;
  job.synthetic.frames = job.frames;
  c.maxFrames = job.framesGiven ? job.frames : -1;
  // A run scores nothing against the truth's per-pixel maps (its view shows
  // the head pose and the people's truth only): they are not computed.
  job.synthetic.scene.pixelTruth = false;
  return job;
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

  // Writes the last frame's still when the source's length was not known,
  // and closes the video.
  void finish() {
    if (!lastView_.empty()) writeStill(lastView_, lastIndex_);
    if (video_) video_->close();
  }

  std::int64_t framesDone() const { return done_; }

  void operator()(const Frame& f) {
    ++done_;
    const double seconds = std::chrono::duration<double>(SteadyClock::now() - start_).count();
    const double fps = seconds > 0 ? static_cast<double>(done_) / seconds : 0;
    const bool still = f.index == 0 || f.index == expected_ / 2 || f.index + 1 == expected_;
    // Drawing a view costs a few ms of CPU (text above all): only for the
    // video, the window, the stills, and the last frame when the length is
    // not known. A view for the video alone is drawn at the video's size.
    if (job_.until.empty() && (job_.video || job_.display || still || expected_ <= 0)) {
      const bool videoOnly = !job_.display && !still && expected_ > 0;
      const cv::Mat view =
          annotateFrame(f, job_.config.stereo, fps, videoOnly ? job_.videoScale : 1);
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
    writeImageFile(job_.outDir + "/still_" + std::to_string(index) + ".png", view, "still");
    lastView_.release();
  }

  void writeVideo(const cv::Mat& view) {
    if (!video_)
      video_ = std::make_unique<VideoRecorder>(job_.outDir + "/run.avi", 30, job_.videoScale);
    video_->write(view);
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
  std::unique_ptr<VideoRecorder> video_;
  cv::Mat lastView_;
  std::int64_t lastIndex_ = 0;
};

// Capture to the end of the stage that commands the head: the robot's
// drivers when there is a robot, else the closed loop's head control.
std::optional<double> glassToCommandMs(const Frame& f) {
  const StageSpan* command = nullptr;
  for (const StageSpan& span : f.spans)
    if (span.stage == "robot" || (span.stage == "head control" && !command)) command = &span;
  if (!command) return std::nullopt;
  return std::chrono::duration<double, std::milli>(command->end - f.captured).count();
}

struct LatencyFigures {
  std::int64_t frames = 0;
  double medianMs = 0, p95Ms = 0;
};

LatencyFigures latencyFigures(std::vector<double> ms) {
  LatencyFigures out;
  out.frames = static_cast<std::int64_t>(ms.size());
  if (ms.empty()) return out;
  std::sort(ms.begin(), ms.end());
  out.medianMs = ms[ms.size() / 2];
  out.p95Ms = ms[std::min(ms.size() - 1, ms.size() * 95 / 100)];
  return out;
}

void printSummary(const RunSummary& s, const RunJob& job, const std::string& backendName,
                  double meanSearched, const LatencyFigures& command) {
  std::printf("%lld frames in %.2f s: %.1f frames/s end to end, latency %.1f ms (max %.1f)",
              static_cast<long long>(s.completed), s.seconds, s.fps(), s.meanLatencyMs,
              s.maxLatencyMs);
  if (s.dropped > 0) std::printf(", %lld stale frames dropped", static_cast<long long>(s.dropped));
  std::printf("\n%d frame(s) in flight, %s mode, backend %s, %d thread(s)%s\n", job.config.inFlight,
              job.config.live ? "live" : "offline", backendName.c_str(), job.config.threads,
              s.stoppedByRequest ? ", stopped by request" : "");
  if (command.frames > 0)
    std::printf("glass to command (capture to the head command): median %.1f ms, p95 %.1f ms\n",
                command.medianMs, command.p95Ms);
  if (job.config.zoneSearch.enabled && meanSearched > 0)
    std::printf("zone search: %.1f of %d disparities searched per frame on average\n", meanSearched,
                job.config.stereo.numDisparities);
  std::printf("%-28s %8s %10s\n", "stage", "ms/frame", "frames/s");
  for (const auto& st : s.stages)
    std::printf("%-28s %8.2f %10.1f\n", st.name.c_str(), st.meanMs, st.fps());
}

}  // namespace

int runPipeline(Args& args) {
  if (args.flag("--help") || args.flag("-h")) {
    std::cout << kRunHelpStart << commandOptionsHelp(kOptions)
              << "Election of the godfather (the person the robot follows):\n"
              << optionFlagsHelp(electionOptions(), ElectionOptions{}) << "\n"
              << stereoFlagsHelp(runStereoDefaults(), MedianParams{},
                                 "all cores with one frame in flight, all but one with more")
              << "Zone-limited matching (each frame searches only where the zone can be):\n"
              << optionFlagsHelp(zoneSearchOptions(), ZoneSearch{});
    return 0;
  }
  // From here a stop signal ends the run cleanly, even during the setup.
  gInterrupted = false;
  const StopSignals signals;
  RunJob job = parseRun(args);
  PipelineConfig& c = job.config;
  const bool detect = c.detection && job.until.empty();
  if (detect && job.movement) {
    if (!job.json)
      std::cerr << "horopter run: movement model " << (job.model.empty() ? "(default)" : job.model)
                << "\n";
    c.movement = loadOrTrainMovementModel(job.model);
  }

  const std::int64_t expected =
      job.framesGiven ? job.frames : (c.source == "synthetic" ? job.synthetic.frames : -1);
  Output output(job, expected);
  std::uint64_t digest = 0;
  double searched = 0;  // disparities searched, summed over the frames
  std::int64_t matched = 0;
  std::vector<double> commandLatencyMs;  // capture to the head command, per frame
  PipelineHooks hooks;
  hooks.onFrame = [&output, &digest, &searched, &matched, &commandLatencyMs](const Frame& f) {
    digest = foldDigest(digest, frameDigest(f));
    if (const auto ms = glassToCommandMs(f)) commandLatencyMs.push_back(*ms);
    if (!f.disparity.empty()) {
      searched += f.searchRange.numDisparities;
      ++matched;
    }
    output(f);
  };
  hooks.stopRequested = &gInterrupted;
  hooks.openSource = sim::syntheticSourceOpener(job.synthetic);
  // The simulated robot: commands go through the real drivers; Ctrl-C latches
  // the base's emergency stop at once (the robot stage checks it every frame).
  std::unique_ptr<hw::SimulatedRobot> robot;
  std::unique_ptr<hw::TelemetryLog> telemetry;
  if (job.robot == "sim") {
    robot = std::make_unique<hw::SimulatedRobot>();
    std::filesystem::create_directories(job.outDir);
    telemetry = std::make_unique<hw::TelemetryLog>(job.outDir + "/telemetry.jsonl");
    RobotStageOptions r;
    r.head = &robot->head();
    r.base = &robot->base();
    r.telemetrySource = robot.get();
    r.log = telemetry.get();
    r.emergencyStop = &gInterrupted;
    hooks.extraStages.push_back(makeRobotStage(r));
  }
  AssembledPipeline pipeline = buildPipeline(c, std::move(hooks));
  const Backend& backend = pipeline.backend();
  if (!job.json)
    std::cerr << "horopter run: source " << pipeline.source().name() << ", backend " << backend.name
              << ", " << c.threads << " thread(s), " << c.inFlight << " frame(s) in flight\n";

  RunSummary summary;
  std::string failure;  // a stage's error: the frames done are still closed and summarised
  try {
    summary = pipeline.run();
  } catch (const Error& e) {
    failure = e.what();
  }
  output.finish();
  if (robot) {
    if (summary.stoppedByRequest || !failure.empty()) robot->base().emergencyStop();
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

  // The frames' digest beside the summary: the same configuration gives the
  // same digest from Python and the C API (tests/app/pipeline_parity_test).
  detail::Json summaryObject = detail::Json::parse(summaryJson(summary));
  summaryObject["frames_digest"] = digestText(digest);
  if (matched > 0)
    summaryObject["mean_searched_disparities"] = detail::jsonNumber(searched / matched, 2);
  const LatencyFigures commandLatency = latencyFigures(commandLatencyMs);
  if (commandLatency.frames > 0)
    summaryObject["glass_to_command_ms"] = {
        {"median", detail::jsonNumber(commandLatency.medianMs, 3)},
        {"p95", detail::jsonNumber(commandLatency.p95Ms, 3)},
        {"frames", commandLatency.frames}};
  summaryObject["zone_search"] = c.zoneSearch.enabled != 0;
  if (!failure.empty()) {
    summaryObject["frames"] = output.framesDone();
    summaryObject["error"] = failure;
  }
  const std::string json = detail::jsonText(summaryObject);
  detail::writeFile(job.outDir + "/summary.json", json + "\n", "run summary");
  if (!failure.empty())
    throw Error(failure + " (the " + std::to_string(output.framesDone()) + " frames done are in " +
                job.outDir + ")");
  if (!job.trace.empty()) writeChromeTrace(summary, job.trace);
  if (job.json)
    std::printf("%s\n", json.c_str());
  else
    printSummary(summary, job, backend.name, matched > 0 ? searched / matched : 0, commandLatency);
  return 0;
}

}  // namespace horopter::cli
