// `horopter profile`: where a frame's time goes, per stage, on each backend
// asked for. CPU backends report the wall time of each front-end stage; an
// OpenCL device reports its upload, each kernel and its download from
// OpenCL profiling events (device time), plus the CPU's speckle filter.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <map>
#include <opencv2/imgproc.hpp>

#include "command_options.hpp"
#include "commands.hpp"
#include "horopter/core/error.hpp"
#include "horopter/eval/stereo_eval.hpp"
#include "horopter/sim/synthetic_scene.hpp"
#include "horopter/vision/frontend.hpp"
#include "horopter/vision/opencl_frontend.hpp"
#include "horopter/vision/opencv.hpp"
#include "json_text.hpp"
#include "option_checks.hpp"
#include "report_format.hpp"

namespace horopter::cli {

namespace {

const char* kHelp =
    "Usage: horopter profile [LEFT RIGHT] [--backend LIST] [--frames N] [--warmup N]\n"
    "                        [--size WxH] [--seed S] [--json] [stereo options]\n\n"
    "Runs the stereo front end on each backend of LIST (comma-separated: scalar, avx2,\n"
    "opencl, opencl:N, part of an OpenCL device's name, auto; default auto) and prints a\n"
    "table per backend: mean, median and minimum milliseconds per stage over the timed\n"
    "frames, and the wall time per frame.\n"
    "  CPU backends: prefilter, match, cleanup (left-right check, speckles), median and\n"
    "                horopter mask, in wall time, on --threads threads.\n"
    "  OpenCL:       upload, each kernel and download in device time from OpenCL\n"
    "                profiling events; the speckle filter (on the CPU) in wall time. The\n"
    "                horopter mask is not part of the device-resident front end.\n"
    "Input: a rectified pair of image files (LEFT RIGHT), else --frames frames of the\n"
    "built-in synthetic scene, rendered before timing starts (rendering is not timed).\n"
    "The mask uses a constant threshold (the middle of the search range): its cost does\n"
    "not depend on the values.\n\n"
    "Options:\n";

constexpr CommandOption kOptions[] = {
    {.kind = OptionKind::Text,
     .flag = "--backend",
     .value = "LIST",
     .fallback = FrontendDefaults::backend,
     .help = "backends to profile, comma-separated; every name is checked before the first runs"},
    {.kind = OptionKind::Integer,
     .flag = "--frames",
     .value = "N",
     .min = 1,
     .max = 10000,
     .fallback = "50",
     .help = "timed frames per backend"},
    {.kind = OptionKind::Integer,
     .flag = "--warmup",
     .value = "N",
     .min = 0,
     .max = 1000,
     .fallback = "5",
     .help = "untimed frames first (program builds, caches)"},
    {.kind = OptionKind::Text,
     .flag = "--size",
     .value = "WxH",
     .fallback = "640x480",
     .help = "synthetic scene size, 16x16..8192x8192"},
    {.kind = OptionKind::Integer,
     .flag = "--seed",
     .value = "S",
     .min = 0,
     .max = 2000000000,
     .fallback = "1",
     .help = "synthetic scene seed"},
    {.kind = OptionKind::Switch,
     .flag = "--json",
     .help = "one JSON object on stdout instead of the tables"},
};

struct StageStats {
  std::string name;
  bool onDevice = false;
  std::vector<double> ms;
};

struct BackendProfile {
  std::string name, device;
  std::string note;  // e.g. a fallback to the CPU
  std::vector<StageStats> stages;
  std::vector<double> wallMs;
};

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v)
    s += x;
  return v.empty() ? 0 : s / static_cast<double>(v.size());
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

double minimum(const std::vector<double>& v) {
  return v.empty() ? 0 : *std::min_element(v.begin(), v.end());
}

StageStats& stageNamed(BackendProfile& p, const std::string& name, bool onDevice) {
  for (StageStats& s : p.stages)
    if (s.name == name) return s;
  p.stages.push_back({name, onDevice, {}});
  return p.stages.back();
}

std::vector<std::string> splitList(const std::string& list) {
  std::vector<std::string> out;
  std::stringstream ss(list);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) out.push_back(item);
  if (out.empty()) throw UsageError("--backend needs at least one backend name");
  return out;
}

// OpenCL when the name says so or names no CPU backend (part of a device's
// name, checked by the OpenCL front end); "auto" stays with findBackend().
bool isOpenCl(const std::string& name) {
  if (name.rfind("opencl", 0) == 0) return true;
  if (name == "auto") return false;
  for (const Backend* b : registeredBackends())
    if (b->name == name) return false;
  return true;
}

struct Pair {
  cv::Mat left, right;  // grey
};

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

BackendProfile profileCpu(const std::string& name, const std::vector<Pair>& pairs,
                          const StereoParams& stereo, const MedianParams& medianParams, int threads,
                          int warmup, int frames) {
  const Backend& backend = findBackend(name);
  StereoFrontend frontend(stereo, medianParams, backend, threads);
  BackendProfile p;
  p.name = backend.name;
  p.device = "CPU, " + std::to_string(threads) + " thread(s)";
  const std::int16_t middle =
      static_cast<std::int16_t>(16 * (stereo.minDisparity + stereo.numDisparities / 2));
  const std::vector<std::int16_t> thresholds(static_cast<std::size_t>(pairs[0].left.cols), middle);
  for (int i = 0; i < warmup + frames; ++i) {
    const Pair& pair = pairs[static_cast<std::size_t>(i) % pairs.size()];
    const auto t0 = std::chrono::steady_clock::now();
    frontend.computeDisparity(viewOf(pair.left), viewOf(pair.right));
    frontend.computeMask(thresholds);
    const double wall = msSince(t0);
    if (i < warmup) continue;
    const FrontendTimings& t = frontend.timings();
    stageNamed(p, "prefilter", false).ms.push_back(t.prefilter);
    stageNamed(p, "match", false).ms.push_back(t.match);
    stageNamed(p, "cleanup", false).ms.push_back(t.cleanup);
    stageNamed(p, "median", false).ms.push_back(t.median);
    stageNamed(p, "mask", false).ms.push_back(t.mask);
    p.wallMs.push_back(wall);
  }
  return p;
}

BackendProfile profileOpenCl(const std::string& name, const std::vector<Pair>& pairs,
                             const StereoParams& stereo, const MedianParams& medianParams,
                             int threads, int warmup, int frames) {
  OpenClFrontend frontend(stereo, medianParams, name, 1, threads);
  BackendProfile p;
  p.name = name;
  for (int i = 0; i < warmup + frames; ++i) {
    const Pair& pair = pairs[static_cast<std::size_t>(i) % pairs.size()];
    const auto t0 = std::chrono::steady_clock::now();
    frontend.computeDisparity(viewOf(pair.left), viewOf(pair.right));
    const double wall = msSince(t0);
    if (i < warmup) continue;
    for (const OpenClStageTime& t : frontend.profile())
      stageNamed(p, t.stage, t.onDevice).ms.push_back(t.ms);
    p.wallMs.push_back(wall);
  }
  p.device = frontend.deviceName();
  if (frontend.onCpu()) p.note = "fell back to the CPU: " + frontend.fallbackReason();
  return p;
}

void printTable(const BackendProfile& p) {
  std::printf("\nbackend %s (%s)%s%s\n", p.name.c_str(), p.device.c_str(),
              p.note.empty() ? "" : "\n  note: ", p.note.c_str());
  std::printf("  %-22s %9s %9s %9s %7s\n", "stage", "mean ms", "median", "min", "where");
  for (const StageStats& s : p.stages)
    std::printf("  %-22s %9.3f %9.3f %9.3f %7s\n", s.name.c_str(), mean(s.ms), median(s.ms),
                minimum(s.ms), s.onDevice ? "device" : "cpu");
  const double wall = mean(p.wallMs);
  std::printf("  %-22s %9.3f %9.3f %9.3f   %.0f frames/s\n", "wall per frame", wall,
              median(p.wallMs), minimum(p.wallMs), wall > 0 ? 1000.0 / wall : 0.0);
}

void printJson(const std::vector<BackendProfile>& profiles, const std::string& input, int width,
               int height, int frames) {
  using detail::Json;
  using detail::jsonNumber;
  Json backends = Json::array();
  for (const BackendProfile& p : profiles) {
    Json stages = Json::array();
    for (const StageStats& s : p.stages)
      stages.push_back(Json{{"stage", s.name},
                            {"where", s.onDevice ? "device" : "cpu"},
                            {"mean_ms", jsonNumber(mean(s.ms))},
                            {"median_ms", jsonNumber(median(s.ms))},
                            {"min_ms", jsonNumber(minimum(s.ms))}});
    backends.push_back(Json{{"backend", p.name},
                            {"device", p.device},
                            {"note", p.note},
                            {"wall_ms",
                             {{"mean", jsonNumber(mean(p.wallMs))},
                              {"median", jsonNumber(median(p.wallMs))},
                              {"min", jsonNumber(minimum(p.wallMs))}}},
                            {"stages", std::move(stages)}});
  }
  const Json o{{"input", input},
               {"width", width},
               {"height", height},
               {"frames", frames},
               {"backends", std::move(backends)}};
  writeJsonLine(detail::jsonText(o));
}

cv::Size parseSize(const std::string& text) {
  const ImageSize wh = parseImageSize(text, "--size", {16, 16}, {8192, 8192});
  return {wh.width, wh.height};
}

}  // namespace

int runProfile(Args& args) {
  if (args.flag("--help") || args.flag("-h")) {
    std::cout << kHelp << commandOptionsHelp(kOptions) << "\n"
              << stereoFlagsHelp(StereoParams{}, MedianParams{});
    return 0;
  }
  const CommandOptions o(args, kOptions);
  const std::vector<std::string> backends = splitList(o.text("--backend"));
  const int frames = static_cast<int>(o.integer("--frames"));
  const int warmup = static_cast<int>(o.integer("--warmup"));
  const cv::Size size = parseSize(o.text("--size"));
  const int seed = static_cast<int>(o.integer("--seed"));
  const bool asJson = o.on("--json");
  const StereoParams stereo = parseStereoFlags(args, StereoParams{});
  const MedianParams medianParams = parseMedianFlags(args, MedianParams{});
  const int threads = parseThreads(args);
  const std::vector<std::string> files = args.positionals();
  args.finish("profile");
  if (!files.empty() && files.size() != 2)
    throw UsageError(
        "give a rectified pair as two image paths (LEFT RIGHT), or none for the "
        "synthetic scene");
  if (files.size() == 2) {
    requireFile(files[0], "left image");
    requireFile(files[1], "right image");
  }
  // Every name before the first backend runs. "opencl" stays: without a
  // device its front end falls back to the CPU and says so in the table.
  for (const std::string& name : backends)
    if (name != "opencl") requireBackend(name);

  std::vector<Pair> pairs;
  std::string input;
  if (files.size() == 2) {
    const cv::Mat l = loadColour(files[0], "left image"), r = loadColour(files[1], "right image");
    if (l.size() != r.size()) throw Error("the left and right images differ in size");
    pairs.push_back({toGrey(l), toGrey(r)});
    input = files[0] + " + " + files[1];
  } else {
    synth::SceneOptions options;
    options.width = size.width;
    options.height = size.height;
    options.seed = static_cast<std::uint64_t>(seed);
    synth::SyntheticScene scene(options);
    // A few distinct frames, cycled: enough variety without rendering every timed frame.
    const int distinct = std::min(frames + warmup, 16);
    if (!asJson) std::cerr << "horopter profile: rendering " << distinct << " synthetic frames\n";
    for (int i = 0; i < distinct; ++i) {
      synth::SyntheticFrame f = scene.render(i * 4);
      pairs.push_back({toGrey(f.left), toGrey(f.right)});
    }
    input = "synthetic scene, seed " + std::to_string(seed);
  }
  if (!asJson)
    std::printf(
        "horopter profile: %s, %dx%d, %d disparities, block %d, %d timed frame(s) after "
        "%d warm-up\n",
        input.c_str(), pairs[0].left.cols, pairs[0].left.rows, stereo.numDisparities,
        stereo.blockSize, frames, warmup);

  std::vector<BackendProfile> profiles;
  for (const std::string& name : backends) {
    profiles.push_back(
        isOpenCl(name) ? profileOpenCl(name, pairs, stereo, medianParams, threads, warmup, frames)
                       : profileCpu(name, pairs, stereo, medianParams, threads, warmup, frames));
    if (!asJson) printTable(profiles.back());
  }
  if (asJson) printJson(profiles, input, pairs[0].left.cols, pairs[0].left.rows, frames);
  return 0;
}

}  // namespace horopter::cli
