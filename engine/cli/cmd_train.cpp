// `horopter train`: the movement classifier from synthetic labelled sequences.
#include <unistd.h>

#include <cstdio>
#include <iostream>
#include <string>

#include "commands.hpp"
#include "horopter/core/error.hpp"
#include "horopter/eval/movement_training.hpp"
#include "horopter/movement/movement_classifier.hpp"

namespace horopter::cli {

int runTrain(Args& args) {
  const MovementModelParams defaults;
  if (args.flag("--help") || args.flag("-h")) {
    std::cout
        << "Usage: horopter train [--seed S] [--sequences N] [-o model.hmm] [options]\n\n"
           "Learns the Bayesian movement classifier "
           "(include/horopter/movement/movement_classifier.hpp)\n"
           "from N labelled sequences of the synthetic scene's movement generator, without\n"
           "rendering: the main person's head and hands projected into the left image with\n"
           "tracking-like noise, varied speed, amplitude, handedness and head pose (seeds S to\n"
           "S+N-1). Prints the frames per movement and the frame accuracy on 20 sequences of\n"
           "the tuning range, and writes the model (a versioned text file).\n\n"
           "Seed ranges: training 1000000.., tuning 2000000.., evaluation below 1000000\n"
           "(eval-interaction's trials). Commands without --model train the default model\n"
           "in-process (the defaults below, a few seconds).\n\n"
           "Options:\n"
           "  --seed S               first training seed (default 1000000)\n"
           "  --sequences N          sequences, about 12 s each (default 300)\n"
           "  -o, --output FILE      the model file (default movement.hmm)\n"
           "  --stay P               P(movement stays the same from frame to frame) (default "
        << defaults.stay
        << ")\n"
           "  --evidence-weight W    exponent of each frame's likelihood, (0, 1] (default "
        << defaults.evidenceWeight
        << ")\n"
           "  --threshold T          posterior to decide a movement, (0.5, 1) (default "
        << defaults.decisionThreshold
        << ")\n"
           "  --rearm R              posterior below which it can be decided again (default "
        << defaults.rearmThreshold << ")\n";
    return 0;
  }
  TrainingOptions options;
  const int seed = args.intValue("--seed", static_cast<int>(kTrainingSeedBase));
  options.sequences = args.intValue("--sequences", options.sequences);
  std::string output = args.stringValue("--output", "");
  if (output.empty()) output = args.stringValue("-o", "movement.hmm");
  options.params.stay = args.doubleValue("--stay", defaults.stay);
  options.params.evidenceWeight = args.doubleValue("--evidence-weight", defaults.evidenceWeight);
  options.params.decisionThreshold = args.doubleValue("--threshold", defaults.decisionThreshold);
  options.params.rearmThreshold = args.doubleValue("--rearm", defaults.rearmThreshold);
  args.finish("train");
  if (seed < 0) throw Error("--seed must be >= 0");
  if (options.sequences < 1 || options.sequences > 100000)
    throw Error("--sequences must be within 1..100000");
  options.firstSeed = static_cast<std::uint64_t>(seed);
  if (options.firstSeed < kEvaluationSeedLimit)
    std::cerr << "warning: training seeds " << seed << ".." << seed + options.sequences - 1
              << " overlap the evaluation range (below " << kEvaluationSeedLimit
              << "): scores on those seeds will not be held-out\n";
  // On a terminal the count rewrites its line every tenth; into a file or a
  // pipe (a CI log) a plain line every quarter, never a carriage return.
  const bool tty = isatty(STDERR_FILENO) != 0;
  const int steps = tty ? 10 : 4;
  int lastStep = -1;
  options.progress = [&](int done, int total) {
    const int step = done * steps / total;
    if (step == lastStep) return;
    lastStep = step;
    if (tty) {
      std::fprintf(stderr, "\rtraining: %d/%d sequences", done, total);
      if (done == total) std::fprintf(stderr, "\n");
    } else if (step > 0) {
      std::fprintf(stderr, "training: %d/%d sequences\n", done, total);
    }
  };
  const MovementModel model = trainMovementModel(options);
  std::printf("frames per movement:");
  for (int m = 0; m < kMovementClassCount; ++m)
    std::printf(" %s %lld", movementClassName(static_cast<MovementClass>(m)),
                static_cast<long long>(model.counts().frames[m]));
  std::printf("\n");
  std::vector<LabelledSequence> tuning;
  for (int i = 0; i < 20; ++i)
    tuning.push_back(syntheticSequence(kTuningSeedBase + i));
  std::printf("frame accuracy on 20 tuning sequences (seeds %llu..%llu): %.1f %%\n",
              static_cast<unsigned long long>(kTuningSeedBase),
              static_cast<unsigned long long>(kTuningSeedBase + 19),
              100.0 * frameAccuracy(model, tuning));
  model.save(output);
  std::printf("wrote %s\n", output.c_str());
  return 0;
}

}  // namespace horopter::cli
