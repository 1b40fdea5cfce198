// Labelled sequences from the people generator and training; see
// include/horopter/eval/movement_training.hpp.
#include <cmath>
#include <mutex>

#include "horopter/core/error.hpp"
#include "horopter/eval/movement_training.hpp"
#include "synthetic/people.hpp"
#include "synthetic/rng.hpp"

namespace horopter {

namespace {

constexpr double kPi = 3.14159265358979323846;
// The scene's movement slots (engine/synthetic/people.cpp): 1.25 s of
// movement and 0.15 s of rest, at speed 1.
constexpr double kSlotS = 1.4;

// A standard normal draw (Box-Muller on SplitMix64: the same on every platform).
double gaussian(synth::SplitMix64& rng) {
  const double u1 = std::max(rng.uniform(0, 1), 1e-12), u2 = rng.uniform(0, 1);
  return std::sqrt(-2 * std::log(u1)) * std::cos(2 * kPi * u2);
}

}  // namespace

LabelledSequence syntheticSequence(std::uint64_t seed, const SequenceOptions& o) {
  if (!(o.framesPerSecond > 0)) throw Error("training sequence: frames per second must be > 0");
  synth::SplitMix64 rng(seed ^ 0x6D6F76656D656E74ull);  // "movement"
  synth::PersonParams person = synth::makePeople(seed, false).front();
  person.speed = rng.uniform(o.speedMin, o.speedMax);
  person.amplitude = rng.uniform(o.amplitudeMin, o.amplitudeMax);
  person.leftHanded = rng.coin();
  const double pan = rng.uniform(-o.maxHeadPanRad, o.maxHeadPanRad);
  const double tilt = rng.uniform(-o.maxHeadTiltRad, o.maxHeadTiltRad);
  const double seconds = o.seconds > 0 ? o.seconds : (person.walkS + 8 * kSlotS) / person.speed;

  // The world seen from the rig turned by pan (about y) then tilt (about x).
  const double cp = std::cos(pan), sp = std::sin(pan), ct = std::cos(tilt), st = std::sin(tilt);
  auto toRig = [&](synth::Vec3 w) {
    const double x = cp * w.x - sp * w.z, z1 = sp * w.x + cp * w.z;
    return cv::Point3d(x, ct * w.y - st * z1, st * w.y + ct * z1);
  };
  const LmaOptions cam;  // the scene's default camera
  LabelledSequence seq;
  seq.seed = seed;
  const int frames = static_cast<int>(seconds * o.framesPerSecond);
  BodySample previous;
  int lostFrames[2] = {0, 0};     // frames left without a track, per hand
  int outlierFrames[2] = {0, 0};  // frames left on something else, per hand
  cv::Point3d outlierOffset[2];   // where, from the hand
  for (int i = 0; i < frames; ++i) {
    const double t = i / o.framesPerSecond;
    const synth::PersonPose pose = synth::poseAt(person, t);
    BodySample s;
    s.frame = i;
    s.timeS = t;
    s.godfather = true;
    auto part = [&](synth::Vec3 world, double noiseScale, PartState& out, const PartState& last) {
      if (i > 0 && rng.uniform(0, 1) < o.coastRate) {
        out = last;
        out.observed = false;
        return;
      }
      const cv::Point3d p = toRig(world);
      const cv::Point3d noisy(p.x + noiseScale * o.lateralNoiseM * gaussian(rng),
                              p.y + noiseScale * o.lateralNoiseM * gaussian(rng),
                              p.z + noiseScale * o.depthNoiseM * gaussian(rng));
      out.tracked = out.observed = true;
      out.image = cv::Point2f(
          static_cast<float>(cam.cx + cam.focalPx * (p.x + 0.5 * cam.baselineM) / p.z +
                             o.pixelNoise * gaussian(rng)),
          static_cast<float>(cam.cy + cam.focalPx * p.y / p.z + o.pixelNoise * gaussian(rng)));
      if (rng.uniform(0, 1) >= o.missingDepthRate) out.rig = cv::Point3f(noisy);
    };
    part(pose.head, 0.5, s.head, previous.head);
    part(pose.hand[0], 1.0, s.leftHand, previous.leftHand);
    part(pose.hand[1], 1.0, s.rightHand, previous.rightHand);
    for (int k = 0; k < 2; ++k) {
      if (outlierFrames[k] == 0 && rng.uniform(0, 1) < o.handOutlierRate) {
        outlierFrames[k] = 1 + static_cast<int>(rng.uniform(0, 6));
        outlierOffset[k] = {rng.uniform(-0.4, 0.4), rng.uniform(-0.3, 0.3), rng.uniform(-0.2, 0.2)};
      }
      PartState& p = k ? s.rightHand : s.leftHand;
      if (outlierFrames[k] > 0 && p.tracked) {
        --outlierFrames[k];
        const cv::Point3f d(outlierOffset[k]);
        if (std::isfinite(p.rig.z)) p.rig += d;
        p.image += cv::Point2f(static_cast<float>(cam.focalPx * d.x / 1.3),
                               static_cast<float>(cam.focalPx * d.y / 1.3));
      }
      if (lostFrames[k] == 0 && rng.uniform(0, 1) < o.handLossRate)
        lostFrames[k] = 3 + static_cast<int>(rng.uniform(0, 18));
      if (lostFrames[k] > 0) {
        --lostFrames[k];
        (k ? s.rightHand : s.leftHand) = PartState{};
      }
    }
    seq.samples.push_back(s);
    seq.labels.push_back(static_cast<MovementClass>(static_cast<int>(pose.movement)));
    previous = s;
  }
  return seq;
}

MovementModel trainMovementModel(const TrainingOptions& options) {
  if (options.sequences < 1) throw Error("training needs at least one sequence");
  MovementCounts counts;
  for (int i = 0; i < options.sequences; ++i) {
    const LabelledSequence seq =
        syntheticSequence(options.firstSeed + static_cast<std::uint64_t>(i), options.sequence);
    LmaExtractor lma(options.lma);
    for (std::size_t k = 0; k < seq.samples.size(); ++k)
      counts.add(seq.labels[k], lma.update(seq.samples[k]));
    if (options.progress) options.progress(i + 1, options.sequences);
  }
  return MovementModel(std::move(counts), options.params);
}

std::shared_ptr<const MovementModel> defaultMovementModel() {
  static std::mutex mutex;
  static std::shared_ptr<const MovementModel> model;
  std::lock_guard<std::mutex> lock(mutex);
  if (!model) model = std::make_shared<const MovementModel>(trainMovementModel({}));
  return model;
}

std::shared_ptr<const MovementModel> loadOrTrainMovementModel(const std::string& path) {
  if (path.empty()) return defaultMovementModel();
  return std::make_shared<const MovementModel>(MovementModel::load(path));
}

double frameAccuracy(const MovementModel& model, const std::vector<LabelledSequence>& sequences,
                     const LmaOptions& lmaOptions) {
  auto shared = std::make_shared<const MovementModel>(model);
  std::int64_t right = 0, total = 0;
  for (const LabelledSequence& seq : sequences) {
    LmaExtractor lma(lmaOptions);
    MovementClassifier classifier(shared);
    for (std::size_t k = 0; k < seq.samples.size(); ++k) {
      const LmaFeatures f = lma.update(seq.samples[k]);
      const auto step = classifier.update(f);
      if (!f.valid) continue;
      ++total;
      right += step.likeliest == seq.labels[k] ? 1 : 0;
    }
  }
  return total ? static_cast<double>(right) / static_cast<double>(total) : 0.0;
}

}  // namespace horopter
