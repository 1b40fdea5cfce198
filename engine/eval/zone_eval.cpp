#include "horopter/eval/zone_eval.hpp"

#include <memory>
#include <opencv2/imgproc.hpp>

#include "horopter/core/error.hpp"
#include "horopter/eval/tracking_eval.hpp"
#include "horopter/sim/synthetic_scene.hpp"
#include "horopter/vision/frontend.hpp"
#include "horopter/vision/geometry.hpp"
#include "horopter/vision/opencv.hpp"

namespace horopter {

namespace {

double ratio(std::int64_t hits, std::int64_t misses) {
  return hits + misses > 0 ? static_cast<double>(hits) / static_cast<double>(hits + misses) : 1.0;
}

}  // namespace

double MaskAgreement::precision() const {
  return ratio(truePositive, falsePositive);
}
double MaskAgreement::recall() const {
  return ratio(truePositive, falseNegative);
}

void MaskAgreement::add(const cv::Mat& test, const cv::Mat& reference, const cv::Mat& counted) {
  if (test.size() != reference.size() || test.type() != CV_8UC1 || reference.type() != CV_8UC1 ||
      (!counted.empty() && (counted.size() != test.size() || counted.type() != CV_8UC1)))
    throw Error("mask agreement: the masks must be CV_8UC1 of one size");
  for (int y = 0; y < test.rows; ++y) {
    const std::uint8_t* t = test.ptr<std::uint8_t>(y);
    const std::uint8_t* r = reference.ptr<std::uint8_t>(y);
    const std::uint8_t* c = counted.empty() ? nullptr : counted.ptr<std::uint8_t>(y);
    for (int x = 0; x < test.cols; ++x) {
      if (c && !c[x]) continue;
      truePositive += t[x] && r[x];
      falsePositive += t[x] && !r[x];
      falseNegative += !t[x] && r[x];
    }
  }
}

struct ZoneEvaluator::Fronts {
  Fronts(const StereoParams& stereo, const MedianParams& median, const Backend& backend,
         int threads)
      : full(stereo, median, backend, threads),
        zone(stereo, median, backend, threads),
        unguarded(stereo, median, backend, threads) {}
  StereoFrontend full, zone, unguarded;
};

ZoneEvaluator::ZoneEvaluator(const StereoParams& stereo, const MedianParams& median,
                             const ZoneSearch& zone, const Backend& backend, int threads)
    : stereo_(stereo),
      zone_(zone),
      fronts_(std::make_unique<Fronts>(stereo, median, backend, threads)) {
  validate(zone_, stereo_);
}

ZoneEvaluator::~ZoneEvaluator() = default;

void ZoneEvaluator::addFrame(const cv::Mat& leftGrey, const cv::Mat& rightGrey,
                             const std::vector<std::int16_t>& thresholds, const cv::Mat& trueInside,
                             const cv::Mat& truthKnown, ZoneEvalResult& result) {
  fronts_->full.computeDisparity(viewOf(leftGrey), viewOf(rightGrey));
  fronts_->full.computeMask(thresholds);
  const SearchRange range = zoneSearchRange(stereo_, thresholds, zone_);
  fronts_->zone.computeDisparity(viewOf(leftGrey), viewOf(rightGrey), range);
  fronts_->zone.computeMask(thresholds);
  const cv::Mat fullMask = matOf(fronts_->full.mask());
  const cv::Mat zoneMask = matOf(fronts_->zone.mask());
  result.zoneVsFull.add(zoneMask, fullMask);
  if (!trueInside.empty()) {
    result.hasTruth = true;
    result.fullVsTruth.add(fullMask, trueInside, truthKnown);
    result.zoneVsTruth.add(zoneMask, trueInside, truthKnown);
  }
  result.searchedDisparities += range.numDisparities;
  if (zone_.guardStep > 0) {
    result.hasGuard = true;
    const BelowRangeGuard guard = guardBelow(stereo_, range);
    if (guard.step > 0)
      result.checkedDisparities += (range.minDisparity - guard.lowest) / guard.step;
    fronts_->unguarded.computeDisparity(viewOf(leftGrey), viewOf(rightGrey),
                                        {range.minDisparity, range.numDisparities});
    fronts_->unguarded.computeMask(thresholds);
    const cv::Mat unguardedMask = matOf(fronts_->unguarded.mask());
    result.unguardedVsFull.add(unguardedMask, fullMask);
    if (!trueInside.empty()) result.unguardedVsTruth.add(unguardedMask, trueInside, truthKnown);
  }
  ++result.frames;
}

ZoneEvalResult evaluateZoneOnSyntheticTrials(std::uint64_t seed, int trials, int frames,
                                             const StereoParams& stereo, const MedianParams& median,
                                             const ZoneSearch& zone, const Backend& backend,
                                             int threads) {
  if (trials < 1 || frames < 1) throw Error("eval-zone: give at least one trial and one frame");
  ZoneEvaluator evaluator(stereo, median, zone, backend, threads);
  ZoneEvalResult result;
  for (int t = 0; t < trials; ++t) {
    // The closed-loop trial as eval-tracking runs it (the head verges on
    // the godfather), over the full range; each of its frames then runs
    // again through both front ends here.
    TrialOptions trial;
    trial.seed = seed + static_cast<std::uint64_t>(t);
    trial.frames = frames;
    trial.stereo = stereo;
    trial.median = median;
    trial.backend = backend.name;
    runTrackingTrial(trial, DetectionScope::HoropterRegion, {}, [&](const TrialFrame& f) {
      evaluator.addFrame(f.frame.leftGrey, f.frame.rightGrey, f.frame.thresholds, f.truth.inside,
                         {}, result);
    });
  }
  return result;
}

}  // namespace horopter
