// Trajectories and bodies of the people; see people.hpp.
#include "synthetic/people.hpp"

#include <algorithm>
#include <cmath>

#include "synthetic/rng.hpp"
#include "synthetic/room.hpp"

namespace horopter::synth {

namespace {

constexpr double kPi = 3.14159265358979323846;
// One movement slot: the movement, then a rest with the hands down.
constexpr double kMoveS = 1.25, kRestS = 0.15, kRampS = 0.2;
constexpr Movement kSequence[] = {Movement::Circle,    Movement::Pointing,     Movement::WaveLeft,
                                  Movement::WaveRight, Movement::SagittalWave, Movement::ByeBye};
// The person's left is local -x (local: x right, y down, z forward).
constexpr double kSide[2] = {-1.0, 1.0};

double smooth(double s) {
  s = std::clamp(s, 0.0, 1.0);
  return s * s * (3 - 2 * s);
}

// The elbow of a two-bone arm from shoulder s to hand h (local frame); the
// hand is pulled in when out of reach. The elbow bends down and outwards.
Vec3 solveElbow(Vec3 s, Vec3& h, double upper, double fore, double side) {
  Vec3 d = h - s;
  double len = norm(d);
  const double reach = upper + fore - 1e-3;
  if (len > reach) {
    h = s + (reach / len) * d;
    d = h - s;
    len = reach;
  }
  len = std::max(len, 1e-6);
  const Vec3 dir = (1.0 / len) * d;
  const double a = (upper * upper - fore * fore + len * len) / (2 * len);
  const double off = std::sqrt(std::max(0.0, upper * upper - a * a));
  Vec3 pole = Vec3{0.6 * side, 1.0, -0.2};
  pole = normalized(pole - dot(pole, dir) * dir);
  return s + a * dir + off * pole;
}

// The hand's target for `movement` at time u (s) into it, local frame.
Vec3 movementHand(Movement movement, Vec3 shoulder, double side, double u, double scale,
                  double amplitude) {
  const double a = amplitude * scale;
  switch (movement) {
    case Movement::Circle: {
      const double th = 2 * kPi * 0.9 * u;
      const Vec3 c = shoulder + Vec3{-side * 0.08 * scale, 0.12 * scale, 0.32 * scale};
      return c + Vec3{side * 0.17 * a * std::cos(th), 0.17 * a * std::sin(th), 0};
    }
    case Movement::Pointing:
      return shoulder + (0.54 * scale) * normalized(Vec3{side * 0.35, -0.15, 0.9});
    case Movement::WaveLeft:
    case Movement::WaveRight: {
      const double th = 2 * kPi * 1.5 * u;
      const Vec3 c = shoulder + Vec3{side * 0.12 * scale, -0.32 * scale, 0.12 * scale};
      return c + Vec3{side * 0.16 * a * std::sin(th), 0.03 * a * (1 - std::cos(2 * th)), 0};
    }
    case Movement::SagittalWave: {
      const double th = 2 * kPi * 1.1 * u;
      const Vec3 c = shoulder + Vec3{side * 0.05 * scale, 0.05 * scale, 0.32 * scale};
      return c + Vec3{0, -0.06 * a * std::cos(th), 0.16 * a * std::sin(th)};
    }
    case Movement::ByeBye: {
      const double th = 2 * kPi * 2.8 * u;
      const Vec3 c = shoulder + Vec3{side * 0.10 * scale, -0.42 * scale, 0.18 * scale};
      return c + Vec3{side * 0.05 * a * std::sin(th), 0, 0};
    }
    case Movement::None:
      break;
  }
  return shoulder;
}

int activeHand(Movement movement, bool leftHanded) {
  if (movement == Movement::WaveLeft) return 0;
  if (movement == Movement::WaveRight) return 1;
  return leftHanded ? 0 : 1;
}

cv::Vec3f randomCloth(SplitMix64& rng) {
  return {static_cast<float>(rng.uniform(0.3, 1.3)), static_cast<float>(rng.uniform(0.3, 1.1)),
          static_cast<float>(rng.uniform(0.3, 0.9))};  // red kept low: not skin
}

Material noiseMaterial(cv::Vec3f gain, double texelsPerMetre) {
  Material m;
  m.texture = TextureId::Noise;
  m.texelsPerMetre = texelsPerMetre;
  m.gain = gain;
  return m;
}

}  // namespace

std::vector<PersonParams> makePeople(std::uint64_t seed, bool distractor, double stationZ) {
  std::vector<PersonParams> people;
  for (int id = 0; id < (distractor ? 2 : 1); ++id) {
    SplitMix64 rng(seed * 0x100000001B3ull + static_cast<std::uint64_t>(id) * 7919 + 1);
    PersonParams p;
    p.id = id;
    p.speed = rng.uniform(0.85, 1.2);
    p.amplitude = rng.uniform(0.8, 1.2);
    p.height = rng.uniform(1.6, 1.9);
    p.leftHanded = rng.uniform(0, 1) < 0.3;
    p.shirt = randomCloth(rng);
    p.trousers = randomCloth(rng) * 0.6f;
    if (id == 0) {
      p.start = {-0.9 + rng.uniform(-0.1, 0.1), room::kFloorY, 3.6};
      p.station = {rng.uniform(-0.12, 0.12), room::kFloorY, rng.uniform(1.2, 1.4)};
      if (stationZ > 0) p.station.z = stationZ;
      p.walkS = 1.6;
      p.firstMovement = 0;
      p.face = TextureId::Face;
    } else {
      p.start = p.station = {rng.uniform(1.2, 1.4), room::kFloorY, rng.uniform(2.9, 3.2)};
      p.walkS = 0;
      p.firstMovement = 3;
      p.face = TextureId::FaceOther;
    }
    people.push_back(p);
  }
  return people;
}

PersonPose poseAt(const PersonParams& person, double timeS) {
  PersonPose pose;
  const double s = person.height / 1.75;
  const double tau = timeS * person.speed;

  // Where the feet are and whether the person walks.
  double walking = 0;
  Vec3 feet = person.station;
  if (tau < person.walkS) {
    feet = lerp(person.start, person.station, smooth(tau / person.walkS));
    walking = 1;
  }
  if (person.id != 0) feet.x += 0.25 * std::sin(0.4 * tau);  // the distractor sways
  pose.feet = feet;
  pose.yaw = std::atan2(-feet.x, -feet.z);  // faces the robot
  const Mat3 r = rotationY(pose.yaw);
  auto world = [&](Vec3 local) { return feet + r.apply(local); };

  // The movement slot.
  Movement movement = Movement::None;
  double u = 0, weight = 0;
  if (tau >= person.walkS) {
    const double t = tau - person.walkS;
    const double slot = kMoveS + kRestS;
    const long long i = static_cast<long long>(std::floor(t / slot));
    u = t - static_cast<double>(i) * slot;
    if (u < kMoveS) {
      movement = kSequence[(person.firstMovement + i) % 6];
      weight = smooth(u / kRampS) * smooth((kMoveS - u) / kRampS);
    }
  }
  pose.movement = movement;

  const double h = person.height;
  const Vec3 shoulderL{-0.19 * s, -0.82 * h, 0}, shoulderR{0.19 * s, -0.82 * h, 0};
  const Vec3 shoulders[2] = {shoulderL, shoulderR};
  const double upper = 0.30 * s, fore = 0.27 * s;
  const int active = activeHand(movement, person.leftHanded);
  for (int k = 0; k < 2; ++k) {
    const double side = kSide[k];
    // At rest the arms hang, swinging a little while walking.
    Vec3 hand = shoulders[k] +
                Vec3{side * 0.05 * s, 0.54 * s,
                     0.05 * s + walking * 0.12 * s * std::sin(2 * kPi * tau + (k ? 0 : kPi))};
    if (movement != Movement::None && k == active)
      hand = lerp(hand, movementHand(movement, shoulders[k], side, u, s, person.amplitude), weight);
    const Vec3 elbow = solveElbow(shoulders[k], hand, upper, fore, side);
    pose.shoulder[k] = world(shoulders[k]);
    pose.elbow[k] = world(elbow);
    pose.hand[k] = world(hand);
    const Vec3 hip{side * 0.1 * s, -0.5 * h, 0};
    const double stride = walking * 0.18 * s * std::sin(2 * kPi * tau + (k ? kPi : 0));
    pose.hip[k] = world(hip);
    pose.foot[k] = world(Vec3{side * 0.1 * s, -0.05 * s, stride});
  }
  pose.headRadii = Vec3{0.085, 0.115, 0.1} * s;
  pose.head = world({0, -(h - 0.115 * s), 0});
  pose.neck = world({0, -(h - 0.26 * s), 0});
  pose.pelvis = world({0, -0.5 * h, 0});
  pose.torsoRadius = 0.15 * s;
  pose.limbRadius = 0.045 * s;
  pose.handRadius = 0.05 * s;
  return pose;
}

void addPrimitives(const PersonParams& person, const PersonPose& pose,
                   std::vector<Primitive>& out) {
  const cv::Vec3f skin{0.82f, 1.09f, 1.52f};
  const Material skinM = noiseMaterial(skin, 300);
  const Material shirtM = noiseMaterial(person.shirt, 200);
  const Material trousersM = noiseMaterial(person.trousers, 200);

  Material faceM;
  faceM.texture = person.face;
  faceM.mapping = Material::Mapping::Face;
  faceM.texelsPerMetre = texture(person.face).width() / (2 * pose.headRadii.x);
  faceM.gain = person.id == 0 ? cv::Vec3f{30, 40, 55} : cv::Vec3f{25, 30, 35};  // hair
  out.push_back(makeEllipsoid(pose.head, pose.headRadii, pose.yaw, faceM));

  const double s = person.height / 1.75;
  out.push_back(makeCapsule(pose.neck, pose.head, 0.05 * s, skinM));
  // The torso: from the hips to the shoulders' line, its caps included.
  const Vec3 up{0, -1, 0};
  const Vec3 shoulderMid = lerp(pose.shoulder[0], pose.shoulder[1], 0.5);
  out.push_back(makeCapsule(pose.pelvis + (pose.torsoRadius * 0.2) * up,
                            shoulderMid - pose.torsoRadius * up + (0.04 * s) * up, pose.torsoRadius,
                            shirtM));
  for (int k = 0; k < 2; ++k) {
    out.push_back(makeCapsule(pose.shoulder[k], pose.elbow[k], pose.limbRadius, shirtM));
    out.push_back(makeCapsule(pose.elbow[k], pose.hand[k], 0.85 * pose.limbRadius, shirtM));
    const double r = pose.handRadius;
    out.push_back(makeEllipsoid(pose.hand[k], {r, r, r}, pose.yaw, skinM));
    out.push_back(makeCapsule(pose.hip[k], pose.foot[k], 0.07 * s, trousersM));
  }
}

}  // namespace horopter::synth
