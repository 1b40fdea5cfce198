// How much zone-limited matching (horopter/vision/zone_search.hpp) changes
// the zone mask: the zone-limited front end's mask against the full-range
// front end's on the same frames, and both against the true zone where it
// is known (the synthetic scene's truth, or a real pair's ground truth).
// `horopter eval-zone` prints it.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <opencv2/core.hpp>

#include "horopter/kernels/backend.hpp"
#include "horopter/kernels/stereo_params.hpp"
#include "horopter/vision/zone_search.hpp"

namespace horopter {

// Pixel counts of a test mask against a reference mask (255 = inside).
struct MaskAgreement {
  std::int64_t truePositive = 0;   // inside in both
  std::int64_t falsePositive = 0;  // inside in the test only
  std::int64_t falseNegative = 0;  // inside in the reference only
  // 1 when there is nothing to get wrong.
  double precision() const;
  double recall() const;
  // Counts the pixels where `counted` is non-zero (all of them when empty).
  void add(const cv::Mat& test, const cv::Mat& reference, const cv::Mat& counted = {});
};

struct ZoneEvalResult {
  int frames = 0;
  MaskAgreement zoneVsFull;        // the zone-limited mask against the full-range mask
  bool hasTruth = false;           // the two below are filled
  MaskAgreement fullVsTruth;       // the full-range mask against the true zone
  MaskAgreement zoneVsTruth;       // the zone-limited mask against the true zone
  double searchedDisparities = 0;  // summed over frames (mean: / frames)
  // With the guard below the range on (ZoneSearch::guardStep > 0): the
  // disparities it checked, summed over frames, and the zone-limited mask
  // without it against the full-range mask (what the guard changes).
  bool hasGuard = false;
  double checkedDisparities = 0;
  MaskAgreement unguardedVsFull;
  MaskAgreement unguardedVsTruth;  // when hasTruth
};

// Runs both front ends (`full` over the full range of `stereo`, then over
// zoneSearchRange of `thresholds`; with the guard on, a third over the same
// range without it) on a rectified grey pair, masks them with `thresholds`
// and adds the frame to `result`. `trueInside` (CV_8UC1, 255
// inside) may be empty; `truthKnown` (CV_8UC1) limits the truth's pixels.
class ZoneEvaluator {
 public:
  ZoneEvaluator(const StereoParams& stereo, const MedianParams& median, const ZoneSearch& zone,
                const Backend& backend, int threads);
  ~ZoneEvaluator();
  void addFrame(const cv::Mat& leftGrey, const cv::Mat& rightGrey,
                const std::vector<std::int16_t>& thresholds, const cv::Mat& trueInside,
                const cv::Mat& truthKnown, ZoneEvalResult& result);

 private:
  struct Fronts;
  StereoParams stereo_;
  ZoneSearch zone_;
  std::unique_ptr<Fronts> fronts_;
};

// The synthetic scene's closed-loop trials `seed` .. `seed + trials - 1`
// as eval-tracking runs them (the head verging on the person, so the
// thresholds are those `horopter run` computes), `frames` frames each.
ZoneEvalResult evaluateZoneOnSyntheticTrials(std::uint64_t seed, int trials, int frames,
                                             const StereoParams& stereo, const MedianParams& median,
                                             const ZoneSearch& zone, const Backend& backend,
                                             int threads);

}  // namespace horopter
