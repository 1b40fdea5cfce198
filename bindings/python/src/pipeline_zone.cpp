#include "pipeline_zone.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include "horopter/calibration.hpp"
#include "horopter/capture.hpp"
#include "horopter/error.hpp"
#include "horopter/geometry.hpp"
#include "horopter/tracking_eval.hpp"
#include "horopter/vision_stages.hpp"

namespace horopter::python {

namespace {

ZoneSetup calibrated(const ZoneOptions& zone) {
  const StereoCalibration calibration = loadStereoCalibration(zone.calib);
  auto rectifier = std::make_shared<StereoRectifier>(calibration);
  ZoneSetup setup;
  setup.rectify = [rectifier](const cv::Mat& l, const cv::Mat& r, cv::Mat& lo, cv::Mat& ro) {
    rectifier->rectify(l, r);
    lo = rectifier->left().clone();  // the rectifier reuses its buffers
    ro = rectifier->right().clone();
  };
  const RectifiedGeometry g = rectifiedGeometry(calibration);
  setup.rig = g;
  const ViethMuellerCircle circle =
      viethMuellerCircle(g.baseline, fixationAtDistance(g.baseline, zone.fixation));
  setup.thresholds = [g, circle](const Frame&, std::vector<std::int16_t>& out) {
    horopterThresholds(g, circle, out);
  };
  return setup;
}

}  // namespace

ZoneSetup zoneSetup(FrameSource& source, const ZoneOptions& zone, const StereoParams& stereo) {
  if (!zone.calib.empty()) return calibrated(zone);
  ZoneSetup setup;
  if (auto* synthetic = dynamic_cast<SyntheticSource*>(&source)) {
    const synth::SyntheticScene& scene = synthetic->scene();
    setup.thresholds = syntheticZoneThresholds(scene);
    setup.rig = RectifiedGeometry{scene.focalPx(), scene.cx(), scene.baselineM(), scene.cy()};
    setup.framesPerSecond = scene.options().framesPerSecond;
  } else {
    setup.thresholds = fixationDisparityThresholds(stereo, zone.fixationDisparity, zone.focalPx);
  }
  return setup;
}

}  // namespace horopter::python
