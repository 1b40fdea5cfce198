// `horopter train`: the movement classifier from synthetic labelled sequences.
#include <unistd.h>

#include <cstdio>
#include <iostream>
#include <string>

#include "command_options.hpp"
#include "commands.hpp"
#include "horopter/core/error.hpp"
#include "horopter/eval/movement_training.hpp"
#include "horopter/movement/movement_classifier.hpp"
#include "option_checks.hpp"

namespace horopter::cli {

namespace {

const char* kHelp =
    "Usage: horopter train [--seed S] [--sequences N] [-o model.hmm] [options]\n\n"
    "Learns the Bayesian movement classifier (include/horopter/movement/movement_classifier.hpp)\n"
    "from N labelled sequences of the synthetic scene's movement generator, without\n"
    "rendering: the main person's head and hands projected into the left image with\n"
    "tracking-like noise, varied speed, amplitude, handedness and head pose (seeds S to\n"
    "S+N-1). Prints the frames per movement and the frame accuracy on 20 sequences of\n"
    "the tuning range, and writes the model (a versioned text file).\n\n"
    "Seed ranges: training 1000000.., tuning 2000000.., evaluation below 1000000\n"
    "(eval-interaction's trials). Commands without --model train the default model\n"
    "in-process (the defaults below, a few seconds).\n\n"
    "Options:\n";

// The model's defaults are MovementModelParams's; the ranges are the
// model's (MovementModel checks them, and the rearm < threshold rule, before
// training starts).
constexpr CommandOption kOptions[] = {
    {.kind = OptionKind::Integer,
     .flag = "--seed",
     .value = "S",
     .min = 0,
     .max = 2000000000,
     .fallback = "1000000",
     .help = "first training seed"},
    {.kind = OptionKind::Integer,
     .flag = "--sequences",
     .value = "N",
     .min = 1,
     .max = 100000,
     .fallback = "300",
     .help = "sequences, about 12 s each"},
    {.kind = OptionKind::Text,
     .flag = "--output",
     .alias = "-o",
     .value = "FILE",
     .fallback = "movement.hmm",
     .help = "the model file"},
    {.kind = OptionKind::Number,
     .flag = "--stay",
     .value = "P",
     .min = 0,
     .max = 1,
     .fallbackOf = [] { return defaultText(MovementModelParams{}.stay); },
     .help = "P(movement stays the same from frame to frame), above 0 and below 1"},
    {.kind = OptionKind::Number,
     .flag = "--evidence-weight",
     .value = "W",
     .min = 0,
     .max = 1,
     .fallbackOf = [] { return defaultText(MovementModelParams{}.evidenceWeight); },
     .help = "exponent of each frame's likelihood, above 0"},
    {.kind = OptionKind::Number,
     .flag = "--threshold",
     .value = "T",
     .min = 0.5,
     .max = 1,
     .fallbackOf = [] { return defaultText(MovementModelParams{}.decisionThreshold); },
     .help = "posterior to decide a movement, above 0.5 and below 1"},
    {.kind = OptionKind::Number,
     .flag = "--rearm",
     .value = "R",
     .min = 0,
     .max = 1,
     .fallbackOf = [] { return defaultText(MovementModelParams{}.rearmThreshold); },
     .help = "posterior below which it can be decided again, below --threshold"},
};

}  // namespace

int runTrain(Args& args) {
  if (args.flag("--help") || args.flag("-h")) {
    std::cout << kHelp << commandOptionsHelp(kOptions);
    return 0;
  }
  const CommandOptions o(args, kOptions);
  args.finish("train");
  TrainingOptions options;
  const long long seed = o.integer("--seed");
  options.sequences = static_cast<int>(o.integer("--sequences"));
  const std::string output = o.text("--output");
  options.params.stay = o.number("--stay");
  options.params.evidenceWeight = o.number("--evidence-weight");
  options.params.decisionThreshold = o.number("--threshold");
  options.params.rearmThreshold = o.number("--rearm");
  // The open ends of the ranges and the rule across them, from the model
  // itself (an empty model with these parameters), before any training.
  asUsageError([&] { MovementModel(MovementCounts{}, options.params); });
  requireWritableFile(output, "--output");
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
