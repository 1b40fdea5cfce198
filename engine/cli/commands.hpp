// The subcommands of the `horopter` tool. Each returns the process exit code
// and throws horopter::Error for bad input.
#pragma once

#include "args.hpp"

namespace horopter::cli {

int runPipeline(Args& args);
int runDisparity(Args& args);
int runEvalStereo(Args& args);
int runDevices(Args& args);
int runCalibrate(Args& args);
int runRectify(Args& args);
int runGeometry(Args& args);
int runHead(Args& args);
int runBase(Args& args);
int runTrain(Args& args);
int runClassify(Args& args);
int runEvalInteraction(Args& args);
int runEvalTracking(Args& args);
int runEvalZone(Args& args);
int runProfile(Args& args);

}  // namespace horopter::cli
