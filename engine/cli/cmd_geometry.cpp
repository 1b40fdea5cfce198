// `horopter geometry`: the zone of interaction of a calibrated head for one
// fixation, as figures and a top-down picture.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <numbers>
#include <optional>

#include "calibration_io.hpp"
#include "command_options.hpp"
#include "commands.hpp"
#include "geometry/zone_figure.hpp"
#include "horopter/core/error.hpp"
#include "horopter/vision/calibration.hpp"
#include "horopter/vision/geometry.hpp"
#include "io/disparity_images.hpp"
#include "option_checks.hpp"

namespace horopter::cli {

namespace {

const char* kHelp =
    "Usage: horopter geometry --calib calib.yml (--fixation D | --vergence-deg A |\n"
    "                         --pan-deg L,R | --axes) [-o PNG]\n\n"
    "The zone of interaction of the calibrated head: the inside of the Vieth-Mueller circle\n"
    "through both (rectified) camera centres and the fixation point. Prints the fixation, the\n"
    "circle, the zone's depth range on the head's axis and on each camera's optical axis, its\n"
    "width at the fixation distance (and nearer), and the disparity thresholds the mask uses;\n"
    "writes a top-down picture: cameras, fields of view, circle, fixation point.\n"
    "Lengths are in the calibration's unit: that of --square for horopter calibrate (metres\n"
    "for --square 0.025), metres for ROS camera_info files.\n\n"
    "Options (one fixation, in the rectified frame: origin midway between the cameras, z\n"
    "forward):\n";

constexpr CommandOption kOptions[] = {
    {.kind = OptionKind::Text,
     .flag = "--calib",
     .value = "PATH",
     .help = "the calibration: horopter calibrate's file, OpenCV's, or ROS camera_info left.yaml "
             "(+ right.yaml) (docs/calibration.md)"},
    kImageSizeOption,
    {.kind = OptionKind::Number,
     .flag = "--fixation",
     .value = "D",
     .min = 0,
     .max = 1e9,
     .help = "straight ahead at distance D: the zone reaches exactly D on the axis"},
    {.kind = OptionKind::Number,
     .flag = "--vergence-deg",
     .value = "A",
     .min = 0,
     .max = 180,
     .unit = "deg",
     .help = "symmetric vergence: each camera turned inward by A/2 degrees"},
    {.kind = OptionKind::Text,
     .flag = "--pan-deg",
     .value = "L,R",
     .help = "pan of each camera in degrees from straight ahead, positive to the right (the "
             "axes cross in front when L > R)"},
    {.kind = OptionKind::Switch,
     .flag = "--axes",
     .help = "where the calibrated cameras' own optical axes come closest"},
    {.kind = OptionKind::Text,
     .flag = "--out",
     .alias = "-o",
     .value = "PNG",
     .fallback = "out/geometry.png",
     .help = "the picture"},
};

double degToRad(double d) {
  return d * std::numbers::pi / 180.0;
}

// One of the four ways to give the fixation (checked before any work).
struct FixationChoice {
  std::optional<double> distance, vergence;
  std::optional<std::pair<double, double>> pans;
  std::string pansText;
  bool axes = false;
};

FixationChoice parseFixation(const CommandOptions& o) {
  FixationChoice f;
  f.distance = o.optionalNumber("--fixation");
  f.vergence = o.optionalNumber("--vergence-deg");
  f.axes = o.on("--axes");
  if (const auto pans = o.optionalText("--pan-deg")) {
    double l = 0, r = 0;
    char tail = 0;
    if (std::sscanf(pans->c_str(), "%lf,%lf%c", &l, &r, &tail) != 2 || !std::isfinite(l) ||
        !std::isfinite(r))
      throw UsageError("--pan-deg needs two angles in degrees as L,R (e.g. 3,-3), got '" + *pans +
                       "'");
    f.pans = std::pair{l, r};
    f.pansText = *pans;
  }
  const int given =
      (f.distance ? 1 : 0) + (f.vergence ? 1 : 0) + (f.pans ? 1 : 0) + (f.axes ? 1 : 0);
  if (given != 1)
    throw UsageError(
        "give exactly one of --fixation D, --vergence-deg A, --pan-deg L,R or --axes (got " +
        std::to_string(given) + ")");
  return f;
}

Eigen::Vector3d chooseFixation(const FixationChoice& choice, const StereoCalibration& calib,
                               const RectifiedGeometry& g, std::string& how) {
  const auto& [distance, vergence, pans, pansText, axes] = choice;
  if (distance) {
    how = "straight ahead at the requested distance";
    return fixationAtDistance(g.baseline, *distance);
  }
  if (vergence) {
    how = "symmetric vergence " + std::to_string(*vergence) + " deg";
    return fixationFromVergence(g.baseline, degToRad(*vergence));
  }
  if (pans) {
    how = "pan angles " + pansText + " deg";
    return fixationFromPanAngles(g.baseline, degToRad(pans->first), degToRad(pans->second));
  }
  how = "closest approach of the calibrated optical axes";
  const auto [left, right] = opticalAxes(calib);
  return fixationFromAxes(left, right);
}

}  // namespace

int runGeometry(Args& args) {
  if (args.flag("--help") || args.flag("-h")) {
    std::cout << kHelp << commandOptionsHelp(kOptions);
    return 0;
  }
  const CommandOptions o(args, kOptions);
  args.finish("geometry");
  const auto calibPath = o.optionalText("--calib");
  if (!calibPath) throw UsageError("--calib FILE is required (write one with horopter calibrate)");
  const FixationChoice choice = parseFixation(o);
  const std::string out = o.text("--out");
  const ImageSize imageSize = calibrationImageSize(o).value_or(ImageSize{});
  const StereoCalibration calib =
      asUsageError([&] { return loadCalibrationArg(*calibPath, imageSize); });
  requireWritableFile(out, "--out");
  const RectifiedGeometry g = rectifiedGeometry(calib);
  const int width = calib.imageSize.width;
  std::string how;
  const Eigen::Vector3d f = chooseFixation(choice, calib, g, how);

  const ViethMuellerCircle c = viethMuellerCircle(g.baseline, f);
  const ZoneExtent e = zoneExtent(g.baseline, c);
  const double b = g.baseline;
  std::printf("rectified pair: %dx%d, focal %.2f px, principal point (%.2f, %.2f), baseline %.5f\n",
              width, calib.imageSize.height, g.focalPx, g.cx, g.cy, b);
  std::printf("fixation (%s): x %.4f, y %.4f, z %.4f; vergence %.3f deg\n", how.c_str(), f.x(),
              f.y(), f.z(), vergenceAngleAt(b, {f.x(), 0, f.z()}) * 180.0 / std::numbers::pi);
  const double fixU = g.cx + g.focalPx * (f.x() + 0.5 * b) / f.z();
  std::printf("  seen at left column %.1f with disparity %.2f px\n", fixU, g.focalPx * b / f.z());
  std::printf("Vieth-Mueller circle: centre (0, %.4f), radius %.4f\n", c.centreZ, c.radius);
  std::printf(
      "zone depth range: on the head's axis 0 .. %.4f; on each camera's optical axis "
      "0 .. %.4f\n",
      e.farOnAxis, e.farOnCamera);
  std::printf("zone width at the fixation distance %.4f: %.4f", f.z(), zoneWidthAt(c, f.z()));
  if (std::abs(f.x()) < 1e-12) std::printf(" (a fixation straight ahead is the zone's far apex)");
  std::printf("\n  at 25/50/75%% of it: %.4f / %.4f / %.4f; widest %.4f at z %.4f\n",
              zoneWidthAt(c, 0.25 * f.z()), zoneWidthAt(c, 0.5 * f.z()),
              zoneWidthAt(c, 0.75 * f.z()), e.widest, e.widestZ);
  // Both cameras see the head's axis beyond the crossing of the inner edges
  // of their fields of view.
  const double nearLeft = g.focalPx * 0.5 * b / std::max(1e-9, width - 1 - g.cx);
  const double nearRight = g.focalPx * 0.5 * b / std::max(1e-9, g.cx);
  std::printf("both cameras see the head's axis from z %.4f on\n", std::max(nearLeft, nearRight));
  std::vector<std::int16_t> table(static_cast<std::size_t>(width));
  horopterThresholds(g, c, table);
  const auto [lo, hi] = std::minmax_element(table.begin(), table.end());
  const int centre = std::clamp(static_cast<int>(std::lround(g.cx)), 0, width - 1);
  char highest[32] = "none inside";
  if (*hi != INT16_MAX) std::snprintf(highest, sizeof highest, "%.2f", *hi / 16.0);
  std::printf(
      "mask thresholds (inside when disparity >= T): %.4f px at the centre column, "
      "%.4f .. %s px over the %d columns\n",
      table[static_cast<std::size_t>(centre)] / 16.0, *lo / 16.0, highest, width);

  writeImageFile(out, drawZoneTopDown(g, width, c), "figure");
  std::printf("wrote %s\n", out.c_str());
  return 0;
}

}  // namespace horopter::cli
