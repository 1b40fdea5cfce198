// The application's one way to assemble the frame pipeline from a
// configuration: `horopter run`, the Python module, the C API and the
// evaluations all call buildPipeline(), so the same configuration gives the
// same frames whichever of them runs it (tests/app/pipeline_parity_test.cpp).
//
// The pipeline is: capture -> rectify -> disparity -> mask -> detection ->
// tracking -> head control (the synthetic scene's closed loop) -> movement
// -> the caller's extra stages (a robot, a scorer). Which of them run follows
// from the configuration: `stopAfter` cuts it after the front end, `detection`
// switches the interaction half off, `movement` adds the classifier.
#pragma once

#include "horopter/core/export.hpp"

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "horopter/app/frame.hpp"
#include "horopter/app/vision_stages.hpp"
#include "horopter/interaction/detection.hpp"
#include "horopter/interaction/head_control.hpp"
#include "horopter/interaction/tracking.hpp"
#include "horopter/kernels/backend.hpp"
#include "horopter/kernels/stereo_params.hpp"
#include "horopter/vision/capture.hpp"

namespace horopter {

class MovementModel;  // horopter/movement/movement_classifier.hpp

// Where the zone (and the rectification) come from, first that applies:
// a calibration file; the synthetic scene's own rig and vergence; else the
// source is taken as rectified and the zone from a fixation disparity.
struct HOROPTER_API ZoneOptions {
  std::string calib;                          // calibration file (empty: none)
  double fixationDistanceM = 1.5;             // with calib: fixation straight ahead, m, > 0
  std::optional<double> fixationDisparityPx;  // else: on the centre column, px (default:
                                              // the middle of the search range)
  std::optional<double> focalPx;              // ... and the focal length, px (default:
                                              // the image width)
};

// The run's stereo parameters: StereoParams{} with the left band matched
// where at least 16 disparities fit (the kernel API's default leaves those
// columns invalid, as cv::StereoBM does): a hand near the image's left edge
// keeps its disparity, so its zone (issue 20; kernels/README.md).
HOROPTER_API StereoParams runStereoDefaults();

// How far the pipeline goes: the whole of it, or only the front end up to a
// stage (profiling; no detection then).
enum class StopAfter { Everything, Rectify, Disparity, Mask };

struct HOROPTER_API PipelineConfig {
  // Capture: a source spec (see openSource, or a source opener's) and its options.
  std::string source = "synthetic";
  CaptureOptions capture;
  std::int64_t maxFrames = -1;  // stop after this many frames (-1: the source's end)
  // Schedule.
  bool live = false;  // live mode: capture never waits, stale frames are dropped
  int inFlight = 3;   // frames in flight, 1..64
  // Front end.
  StereoParams stereo = runStereoDefaults();
  MedianParams median;
  std::string backend = "auto";  // scalar, avx2, opencl..., auto
  int threads = 1;               // the disparity stage's threads, 1..256
  ZoneOptions zone;
  ZoneSearch zoneSearch;  // each frame's search range from its zone (off: the full range)
  StopAfter stopAfter = StopAfter::Everything;
  // Interaction. Detection over the horopter's region or the full image;
  // nothing: no detection, tracking or movement.
  std::optional<DetectionScope> detection = DetectionScope::HoropterRegion;
  DetectorOptions detector;  // its scope is `detection`'s
  // The builder fills the tracker's rig, frame rate, largest disparity,
  // clock (capture time when live) and, in the closed loop, capture pose.
  TrackerOptions tracker;
  // A steerable source (the simulator's rig) in closed loop: the head
  // control turns its cameras (offline, without a calibration file, with
  // detection).
  bool headControl = true;
  HeadControlOptions head;
  bool followHeadTurns = true;                    // tracks move with the image when the head turns
  std::shared_ptr<const MovementModel> movement;  // the classifier (null: none)
};

// A source as an opener delivers it: the frames, and what the source knows
// of itself that the configuration would otherwise have to say.
struct HOROPTER_API OpenedSource {
  std::unique_ptr<FrameSource> source;
  // A source that knows its rig (a simulator): the zone's thresholds for
  // each frame, the rectified geometry and the frame rate of its clock.
  // Empty thresholds: the zone comes from the configuration.
  ThresholdFunction thresholds;
  RectifiedGeometry rig;       // focalPx 0: unknown
  double framesPerSecond = 0;  // 0: the tracker's default
  // A steerable source (closed loop): the stage that turns its cameras,
  // and how a frame tells the pose it was captured with.
  std::function<std::unique_ptr<Stage>(const HeadControlOptions&)> headControl;
  CapturePose capturePose;
};

// Opens the configuration's source if it knows its spec (nothing
// otherwise: the builder then calls openSource). `steerable`: the builder
// wants a source its head control can turn (closed loop), when there is one.
using SourceOpener =
    std::function<std::optional<OpenedSource>(const PipelineConfig& config, bool steerable)>;

// What the caller adds: where finished frames go, a stop flag (Ctrl-C),
// stages after the built ones (a robot, a scorer), and an opener for
// sources the library does not know (the simulator's "synthetic").
struct HOROPTER_API PipelineHooks {
  std::function<void(const Frame&)> onFrame;
  const std::atomic<bool>* stopRequested = nullptr;
  std::vector<std::unique_ptr<Stage>> extraStages;
  SourceOpener openSource;
};

// A pipeline with its source, ready to run once.
class HOROPTER_API AssembledPipeline {
 public:
  AssembledPipeline(AssembledPipeline&&) noexcept;
  AssembledPipeline& operator=(AssembledPipeline&&) noexcept;
  ~AssembledPipeline();

  RunSummary run();
  FrameSource& source();
  const Backend& backend() const;
  bool closedLoop() const;  // the head control turns the source's cameras
  bool detecting() const;   // detection and tracking run

 private:
  friend AssembledPipeline buildPipeline(const PipelineConfig&, PipelineHooks);
  struct Parts;
  explicit AssembledPipeline(std::unique_ptr<Parts> parts);
  std::unique_ptr<Parts> parts_;
};

// Throws horopter::Error for a bad configuration, source or calibration.
HOROPTER_API AssembledPipeline buildPipeline(const PipelineConfig& config,
                                             PipelineHooks hooks = {});

// A digest of what a frame's stages produced: its index, disparity, mask
// and the godfather's tracked parts (FNV-1a, 64 bits; images 8 bytes a
// step). Equal digests over a run mean equal outputs; the parity tests
// compare them across front ends.
HOROPTER_API std::uint64_t frameDigest(const Frame& frame);
// Frame digests folded in frame order.
HOROPTER_API std::uint64_t foldDigest(std::uint64_t runDigest, std::uint64_t frameDigest);
// A digest as the front ends print it: 16 lowercase hex digits.
HOROPTER_API std::string digestText(std::uint64_t digest);

}  // namespace horopter
