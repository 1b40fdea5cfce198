// `horopter geometry`: the zone of interaction of a calibrated head for one
// fixation, as figures and a top-down picture.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <numbers>
#include <optional>

#include "calibration_io.hpp"
#include "commands.hpp"
#include "geometry/zone_figure.hpp"
#include "horopter/core/error.hpp"
#include "horopter/vision/calibration.hpp"
#include "horopter/vision/geometry.hpp"
#include "io/disparity_images.hpp"

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
    "  --calib PATH        the calibration: horopter calibrate's file, OpenCV's, or ROS\n"
    "                      camera_info left.yaml (+ right.yaml) (docs/calibration.md)\n"
    "  --image-size WxH    for a calibration without an image size (stereo_calib's pair)\n"
    "One fixation, in the rectified frame (origin midway between the cameras, z forward):\n"
    "  --fixation D        straight ahead at distance D: the zone reaches exactly D on the axis\n"
    "  --vergence-deg A    symmetric vergence: each camera turned inward by A/2 degrees\n"
    "  --pan-deg L,R       pan of each camera in degrees from straight ahead, positive to the\n"
    "                      right (the axes cross in front when L > R)\n"
    "  --axes              where the calibrated cameras' own optical axes come closest\n"
    "  -o, --out PNG       the picture (default out/geometry.png)\n";

double degToRad(double d) {
  return d * std::numbers::pi / 180.0;
}

Eigen::Vector3d chooseFixation(Args& args, const StereoCalibration& calib,
                               const RectifiedGeometry& g, std::string& how) {
  const auto distance = args.optionalDouble("--fixation");
  const auto vergence = args.optionalDouble("--vergence-deg");
  const auto pans = args.value("--pan-deg");
  const bool axes = args.flag("--axes");
  const int given = (distance ? 1 : 0) + (vergence ? 1 : 0) + (pans ? 1 : 0) + (axes ? 1 : 0);
  if (given != 1)
    throw Error(
        "give exactly one of --fixation D, --vergence-deg A, --pan-deg L,R or --axes (got " +
        std::to_string(given) + ")");
  if (distance) {
    how = "straight ahead at the requested distance";
    return fixationAtDistance(g.baseline, *distance);
  }
  if (vergence) {
    how = "symmetric vergence " + std::to_string(*vergence) + " deg";
    return fixationFromVergence(g.baseline, degToRad(*vergence));
  }
  if (pans) {
    double l = 0, r = 0;
    char tail = 0;
    if (std::sscanf(pans->c_str(), "%lf,%lf%c", &l, &r, &tail) != 2)
      throw Error("--pan-deg needs two angles in degrees as L,R (e.g. 3,-3), got '" + *pans + "'");
    how = "pan angles " + *pans + " deg";
    return fixationFromPanAngles(g.baseline, degToRad(l), degToRad(r));
  }
  how = "closest approach of the calibrated optical axes";
  const auto [left, right] = opticalAxes(calib);
  return fixationFromAxes(left, right);
}

}  // namespace

int runGeometry(Args& args) {
  if (args.flag("--help") || args.flag("-h")) {
    std::cout << kHelp;
    return 0;
  }
  const auto calibPath = args.value("--calib");
  if (!calibPath) throw Error("--calib FILE is required (write one with horopter calibrate)");
  const StereoCalibration calib =
      loadCalibrationArg(*calibPath, parseCalibrationImageSize(args).value_or(ImageSize{}));
  const RectifiedGeometry g = rectifiedGeometry(calib);
  const int width = calib.imageSize.width;
  std::string how;
  const Eigen::Vector3d f = chooseFixation(args, calib, g, how);
  const std::string out = args.stringValue("-o", args.stringValue("--out", "out/geometry.png"));
  args.finish("geometry");

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

  const std::filesystem::path parent = std::filesystem::path(out).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
  writeImageFile(out, drawZoneTopDown(g, width, c), "figure");
  std::printf("wrote %s\n", out.c_str());
  return 0;
}

}  // namespace horopter::cli
