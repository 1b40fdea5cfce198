// Command options that several commands take with one meaning: declared here
// once and listed in each command's table (command_options.hpp).
#pragma once

#include "command_options.hpp"
#include "horopter/vision/frontend.hpp"

namespace horopter::cli {

// The front end's backend (every backend gives the reference's output).
inline constexpr CommandOption kBackendOption = {
    .kind = OptionKind::Text,
    .flag = "--backend",
    .value = "B",
    .fallback = FrontendDefaults::backend,
    .help = "scalar, avx2, opencl, opencl:N or auto (horopter devices lists them)"};

// The trials' detection scope (eval-tracking, eval-interaction).
inline constexpr CommandOption kTrialScopeOption = {.kind = OptionKind::Choice,
                                                    .flag = "--scope",
                                                    .value = "S",
                                                    .fallback = "both",
                                                    .choices = "region,full,both",
                                                    .help = "where faces and hands are detected"};

// A trial's disparity threads; trials themselves run --jobs at a time.
inline constexpr CommandOption kTrialThreadsOption = {.kind = OptionKind::Integer,
                                                      .flag = "--threads",
                                                      .value = "N",
                                                      .min = 1,
                                                      .max = 256,
                                                      .fallback = "1",
                                                      .help = "threads of the disparity stage"};

// Trials run N at a time (eval-tracking, eval-interaction).
inline constexpr CommandOption kTrialJobsOption = {
    .kind = OptionKind::Integer,
    .flag = "--jobs",
    .value = "N",
    .min = 1,
    .max = 64,
    .fallback = "1",
    .help =
        "trials run N at a time; the scores do not depend on it, the times do (the trials "
        "compete for the cores)"};

// How head control turns the 3-D head point into pan and tilt.
inline constexpr CommandOption kHeadFormulaOption = {
    .kind = OptionKind::Choice,
    .flag = "--head-formula",
    .value = "F",
    .fallback = "atan2",
    .choices = "atan2,paper",
    .help =
        "the head's angles from the 3-D head point (atan2) or the paper's tan = u / (d lambda "
        "f)"};

// The zone of a pair rectified already (no calibration): its fixation
// disparity and focal length.
inline constexpr CommandOption kFixationDisparityOption = {
    .kind = OptionKind::Number,
    .flag = "--fixation-disparity",
    .value = "D",
    .min = 1e-3,
    .max = 1e6,
    .unit = "px",
    .help =
        "disparity of the fixation point on the centre column, for a pair rectified already "
        "(no --calib); the Vieth-Mueller circle passes through it and both cameras (default: "
        "the middle of the search range)"};
inline constexpr CommandOption kFocalPxOption = {
    .kind = OptionKind::Number,
    .flag = "--focal-px",
    .value = "F",
    .min = 1e-3,
    .max = 1e7,
    .unit = "px",
    .help = "focal length of a pair rectified already (no --calib) (default: the image width)"};

}  // namespace horopter::cli
