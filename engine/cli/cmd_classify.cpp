// `horopter classify`: movement decisions and robot actions for a recorded
// track or for synthetic labelled sequences (scored against their labels).
#include <cstdio>
#include <iostream>
#include <string>

#include "command_options.hpp"
#include "commands.hpp"
#include "horopter/app/interaction_stages.hpp"
#include "horopter/core/error.hpp"
#include "horopter/eval/movement_scoring.hpp"
#include "horopter/eval/movement_training.hpp"
#include "horopter/eval/tracking_eval.hpp"
#include "horopter/movement/body_track_file.hpp"
#include "horopter/movement/movement.hpp"
#include "json_text.hpp"
#include "option_checks.hpp"
#include "report_format.hpp"

namespace horopter::cli {

namespace {

// "S" or "S:N", the value of `option`.
void parseSeedRange(const std::string& text, const std::string& option, std::uint64_t& first,
                    int& count) {
  const auto colon = text.find(':');
  try {
    std::size_t used = 0;
    const std::string a = text.substr(0, colon);
    first = std::stoull(a, &used);
    if (used != a.size()) throw std::invalid_argument("");
    count = 1;
    if (colon != std::string::npos) {
      const std::string b = text.substr(colon + 1);
      count = std::stoi(b, &used);
      if (used != b.size()) throw std::invalid_argument("");
    }
  } catch (const std::exception&) {
    throw UsageError(option + " takes SEED or SEED:COUNT, got '" + text + "'");
  }
  if (count < 1 || count > 100000)
    throw UsageError(option + " SEED:COUNT needs COUNT within 1..100000");
}

detail::Json posteriorJson(const MovementPosterior& p) {
  detail::Json o = detail::Json::object();
  for (int m = 0; m < kMovementClassCount; ++m)
    o[movementClassName(static_cast<MovementClass>(m))] = detail::jsonNumber(p[m], 4);
  return o;
}

// One rendered trial through the whole pipeline, decisions printed as the
// frames come out of it, then scored against the scene's truth.
int classifyLive(std::uint64_t seed, int frames, DetectionScope scope, int grace,
                 std::shared_ptr<const MovementModel> model, bool quiet) {
  TrialOptions trial;
  trial.seed = seed;
  trial.frames = frames;
  std::vector<std::unique_ptr<Stage>> extra;
  extra.push_back(makeMovementStage(std::move(model)));
  std::vector<ScoredFrame> scored;
  int decisions = 0;
  const TrialResult r = runTrackingTrial(trial, scope, std::move(extra), [&](const TrialFrame& tf) {
    ScoredFrame f;
    f.truth = static_cast<MovementClass>(static_cast<int>(tf.truth.people.at(0).movement));
    f.onTarget = tf.frame.body.godfather && !tf.lost;
    f.interacting = tf.truthGodfather;
    const MovementState* st = tf.frame.movement.get();
    if (st && st->decision) {
      f.decision = st->decision;
      ++decisions;
      if (!quiet)
        std::printf("frame %5lld  t %7.2f s  %-14s p %.3f  -> %s   (truth: %s)\n",
                    static_cast<long long>(tf.frame.index), tf.frame.body.timeS,
                    movementClassName(*st->decision),
                    st->posterior[static_cast<int>(*st->decision)],
                    st->actionStarted ? robotActionName(st->action) : "(ignored)",
                    movementClassName(f.truth));
      std::fflush(stdout);
    }
    scored.push_back(f);
  });
  const MovementScore score = summariseSegments(scored, grace);
  std::printf("%d decisions in %lld frames (%s, %.1f frames/s)\n", decisions,
              static_cast<long long>(r.summary.completed), detectionScopeName(scope),
              r.summary.fps());
  std::printf(
      "movements %d, tracker lost in %d, correctly classified %d (%.1f %%), real %.1f %%, "
      "spurious decisions %d\n",
      score.segments, score.lost, score.correctTracked, score.classificationPct(),
      score.realClassificationPct(), score.spurious);
  return 0;
}

constexpr CommandOption kOptions[] = {
    {.kind = OptionKind::Heading, .flag = "Input"},
    {.kind = OptionKind::Text,
     .flag = "--track",
     .value = "FILE",
     .help = "a recorded body track (CSV, body_track_file.hpp); scored like --synthetic when "
             "it has a truth column (eval-interaction --write-tracks DIR writes such tracks "
             "from rendered trials)"},
    {.kind = OptionKind::Text,
     .flag = "--synthetic",
     .value = "S[:N]",
     .help = "N labelled sequences of the synthetic movement generator (ground-truth poses "
             "with tracking-like noise, no rendering), seeds S..S+N-1 (N 1..100000); also "
             "scored per movement against the labels (classification rate, spurious "
             "decisions)"},
    {.kind = OptionKind::Text,
     .flag = "--live",
     .value = "SEED",
     .help = "a live run: the synthetic scene rendered with seed SEED through the whole "
             "pipeline (stereo, detection, tracking, head control, movement), decisions "
             "printed as they come, then scored against the scene's truth"},
    {.kind = OptionKind::Heading, .flag = "Options"},
    {.kind = OptionKind::Integer,
     .flag = "--frames",
     .value = "N",
     .min = 30,
     .max = 100000,
     .fallback = "300",
     .help = "--live: frames to run (300: 10 s)"},
    {.kind = OptionKind::Choice,
     .flag = "--scope",
     .value = "S",
     .fallback = "region",
     .choices = "region,full",
     .help = "--live: detection in the horopter's region or the full image"},
    {.kind = OptionKind::Text,
     .flag = "--model",
     .value = "FILE",
     .help = "the model (default: the default model, trained in-process from seeds "
             "1000000..1000299)"},
    {.kind = OptionKind::Text,
     .flag = "--write-track",
     .value = "FILE",
     .help = "with --synthetic (one sequence): write it as a track file"},
    {.kind = OptionKind::Integer,
     .flag = "--grace-frames",
     .value = "N",
     .min = 0,
     .max = 300,
     .fallback = "15",
     .help = "scoring: frames after a movement's end where its decision still counts"},
    {.kind = OptionKind::Switch, .flag = "--quiet", .help = "print only the summary"},
    {.kind = OptionKind::Switch,
     .flag = "--json",
     .help = "one JSON object: decisions (and score)"},
};

}  // namespace

int runClassify(Args& args) {
  if (args.flag("--help") || args.flag("-h")) {
    std::cout
        << "Usage: horopter classify (--track FILE | --synthetic SEED[:COUNT] | --live SEED)\n"
           "                         [options]\n\n"
           "Runs the movement chain (LMA features, the Bayesian classifier, the behaviour\n"
           "layer) and prints each decision with its posterior and the robot's action.\n\n"
        << commandOptionsHelp(kOptions)
        << "For the whole pipeline on rendered trials, see horopter eval-interaction.\n";
    return 0;
  }
  const CommandOptions o(args, kOptions);
  args.finish("classify");
  const std::string track = o.text("--track");
  const std::string synthetic = o.text("--synthetic");
  const std::string live = o.text("--live");
  const std::string modelPath = o.text("--model");
  const std::string writeTrack = o.text("--write-track");
  const int grace = static_cast<int>(o.integer("--grace-frames"));
  const bool quiet = o.on("--quiet");
  const bool json = o.on("--json");
  if (int(!track.empty()) + int(!synthetic.empty()) + int(!live.empty()) != 1)
    throw UsageError(
        "classify needs exactly one of --track FILE, --synthetic SEED[:COUNT] or --live SEED");
  if (!modelPath.empty()) requireFile(modelPath, "movement model");
  if (!live.empty()) {
    std::uint64_t seed = 0;
    int count = 0;
    parseSeedRange(live, "--live", seed, count);
    if (count != 1) throw UsageError("--live runs one scene: give one SEED");
    if (json || !writeTrack.empty())
      throw UsageError("--live prints text only (no --json, --write-track)");
    return classifyLive(
        seed, static_cast<int>(o.integer("--frames")),
        o.text("--scope") == "full" ? DetectionScope::FullImage : DetectionScope::HoropterRegion,
        grace, loadOrTrainMovementModel(modelPath), quiet);
  }
  if (o.given("--frames") || o.given("--scope"))
    throw UsageError("--frames and --scope are for --live");
  if (!writeTrack.empty() && synthetic.empty()) throw UsageError("--write-track needs --synthetic");
  std::uint64_t first = 0;
  int count = 0;
  if (!synthetic.empty()) {
    parseSeedRange(synthetic, "--synthetic", first, count);
    if (!writeTrack.empty() && count != 1)
      throw UsageError("--write-track writes one sequence: use --synthetic SEED");
    if (!writeTrack.empty()) requireWritableFile(writeTrack, "--write-track");
  } else {
    requireFile(track, "track file");
  }

  std::vector<LabelledSequence> inputs;
  bool labelled = false;
  if (!track.empty()) {
    LabelledSequence s;
    s.samples = readBodyTrack(track, &s.labels);
    if (s.samples.empty()) throw Error("track file '" + track + "' has no samples");
    labelled = !s.labels.empty();
    inputs.push_back(std::move(s));
  } else {
    const TrainingOptions defaults;
    if (modelPath.empty() && first < defaults.firstSeed + defaults.sequences &&
        first + count > defaults.firstSeed)
      std::cerr << "warning: seeds " << first << ".." << first + count - 1
                << " include the default model's training seeds\n";
    for (int i = 0; i < count; ++i)
      inputs.push_back(syntheticSequence(first + i));
    if (!writeTrack.empty()) {
      writeBodyTrack(writeTrack, inputs.front().samples, inputs.front().labels);
      std::cerr << "wrote " << writeTrack << "\n";
    }
    labelled = true;
  }

  const auto model = loadOrTrainMovementModel(modelPath);
  MovementScore score;
  detail::Json decisionsJson = detail::Json::array();
  int decisions = 0;
  for (const LabelledSequence& seq : inputs) {
    const std::vector<MovementState> states = classifyTrack(seq.samples, model);
    std::vector<ScoredFrame> scored;
    for (std::size_t i = 0; i < states.size(); ++i) {
      const MovementState& st = states[i];
      const BodySample& s = seq.samples[i];
      if (labelled) scored.push_back({seq.labels[i], st.decision, true});
      if (!st.decision) continue;
      const int d = static_cast<int>(*st.decision);
      if (json) {
        decisionsJson.push_back(
            detail::Json{{"sequence", seq.seed},
                         {"frame", s.frame},
                         {"time_s", detail::jsonNumber(s.timeS, 3)},
                         {"movement", movementClassName(*st.decision)},
                         {"action", st.actionStarted ? robotActionName(st.action) : "ignored"},
                         {"posterior", posteriorJson(st.posterior)}});
      } else if (!quiet) {
        std::printf("%sframe %5lld  t %7.2f s  %-14s p %.3f  -> %s%s\n",
                    labelled ? ("seed " + std::to_string(seq.seed) + "  ").c_str() : "",
                    static_cast<long long>(s.frame), s.timeS, movementClassName(*st.decision),
                    st.posterior[d], st.actionStarted ? robotActionName(st.action) : "(ignored: ",
                    st.actionStarted        ? ""
                    : st.interactionStopped ? "interaction stopped)"
                                            : "cool-down)");
        if (labelled) std::printf("      truth: %s\n", movementClassName(seq.labels[i]));
      }
      ++decisions;
    }
    if (labelled) score.add(summariseSegments(scored, grace));
  }
  if (json) {
    detail::Json out{{"decisions", std::move(decisionsJson)}};
    if (labelled)
      out["score"] = {{"movements", score.segments},
                      {"correct", score.correct},
                      {"classification_rate", detail::jsonNumber(score.classificationPct(), 2)},
                      {"spurious", score.spurious}};
    writeJsonLine(detail::jsonText(out));
    return 0;
  }
  std::printf("%d decisions over %zu sequence(s)\n", decisions, inputs.size());
  if (labelled)
    std::printf("movements %d, correctly classified %d (%.1f %%), spurious decisions %d\n",
                score.segments, score.correct, score.classificationPct(), score.spurious);
  return 0;
}

}  // namespace horopter::cli
