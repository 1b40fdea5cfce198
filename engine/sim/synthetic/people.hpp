// The people: per-person variability drawn from the seed, head and hand
// trajectories for the six movements, and the body built from primitives.
//
// The main person (id 0) walks from the back of the room into the zone and
// then performs Circle, Pointing, WaveLeft, WaveRight, SagittalWave and
// ByeBye in turn, each followed by a short rest, and starts over. The
// distractor (id 1) sways at the side of the room, outside the zone, and
// performs the same movements in another order.
#pragma once

#include <cstdint>
#include <vector>

#include "horopter/sim/synthetic_scene.hpp"
#include "synthetic/primitives.hpp"
#include "synthetic/vec3.hpp"

namespace horopter::synth {

struct PersonParams {
  int id = 0;
  double speed = 1;      // time scale of walking and movements
  double amplitude = 1;  // size of the hand movements
  double height = 1.75;  // metres
  bool leftHanded = false;
  Vec3 start, station;        // feet positions (world): walk from start to station
  double walkS = 1.6;         // seconds (before the speed scale) of the walk
  int firstMovement = 0;      // where in the list of six the sequence starts
  cv::Vec3f shirt, trousers;  // BGR gains of the clothes
  TextureId face = TextureId::Face;
};

// The two people of a scene with seed `seed` (the distractor only when asked);
// `stationZ` > 0 places the main person at that depth instead of 1.2-1.4 m.
std::vector<PersonParams> makePeople(std::uint64_t seed, bool distractor, double stationZ = 0);

// Joint positions at one instant, world coordinates.
struct PersonPose {
  Vec3 feet;       // on the floor, between the feet
  double yaw = 0;  // facing direction: the person faces the robot
  Vec3 head, neck, pelvis;
  Vec3 shoulder[2], elbow[2], hand[2];  // [0] left, [1] right (the person's own)
  Vec3 hip[2], foot[2];
  Movement movement = Movement::None;
  // Body sizes (scaled with height).
  Vec3 headRadii;
  double torsoRadius = 0, limbRadius = 0, handRadius = 0;
};

PersonPose poseAt(const PersonParams& person, double timeS);

// Appends the person's primitives (head ellipsoid with the face, neck,
// torso, arms, hands, legs).
void addPrimitives(const PersonParams& person, const PersonPose& pose, std::vector<Primitive>& out);

}  // namespace horopter::synth
