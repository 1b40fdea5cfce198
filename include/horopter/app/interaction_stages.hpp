// The stages of the interaction and movement layers: each runs its layer's
// algorithm on the Frame and fills the field named below.
#pragma once

#include "horopter/core/export.hpp"

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>

#include "horopter/app/frame.hpp"
#include "horopter/hardware/head.hpp"
#include "horopter/interaction/detection.hpp"
#include "horopter/interaction/head_control.hpp"
#include "horopter/interaction/tracking.hpp"
#include "horopter/movement/movement.hpp"

namespace horopter {

// "detection": fills Frame::detections (Detector).
HOROPTER_API std::unique_ptr<Stage> makeDetectionStage(DetectorOptions options);

// "tracking": fills Frame::tracking and Frame::body (BodyTracker). Needs the
// detection stage before it.
HOROPTER_API std::unique_ptr<Stage> makeTrackingStage(TrackerOptions options);

// Where head commands go: (frame they were computed from, command or none).
using HeadCommandSink = std::function<void(std::int64_t, const std::optional<hw::HeadAngles>&)>;

// "head control": the command of headCommand() from the pose at capture.
// Needs Frame::tracking; posts every frame (std::nullopt when none) and
// records the command in a copy of Frame::tracking.
HOROPTER_API std::unique_ptr<Stage> makeHeadControlStage(HeadControlOptions options,
                                                         CapturePose pose, HeadCommandSink sink);

// "movement": LMA features, classification and behaviour (MovementAnalyser)
// from Frame::body; fills Frame::movement. Needs the tracking stage before it.
HOROPTER_API std::unique_ptr<Stage> makeMovementStage(std::shared_ptr<const MovementModel> model,
                                                      MovementStageOptions options = {});

}  // namespace horopter
