// The room's layout and materials; see room.hpp.
#include "synthetic/room.hpp"

namespace horopter::synth::room {

namespace {

Material tiled(TextureId id, double texelsPerMetre, cv::Vec3f gain = {1, 1, 1}) {
  Material m;
  m.texture = id;
  m.texelsPerMetre = texelsPerMetre;
  m.gain = gain;
  return m;
}

// A poster: a thin box whose faces all show the whole image once.
Primitive poster(Vec3 lo, Vec3 hi, TextureId id, double widthM) {
  Material m;
  m.texture = id;
  m.mapping = Material::Mapping::Stretch;
  m.texelsPerMetre = texture(id).width() / widthM;
  return makeBox(lo, hi, m);
}

// A furniture block standing on the floor.
Primitive block(double x0, double x1, double z0, double z1, double height, const Material& m) {
  return makeBox({x0, kFloorY - height, z0}, {x1, kFloorY, z1}, m);
}

}  // namespace

std::vector<Primitive> build(bool furnished, bool skinClutter) {
  std::vector<Primitive> prims;
  Primitive walls;
  walls.shape = Primitive::Shape::Room;
  walls.a = {kLeftX, kCeilingY, kBehindZ};
  walls.b = {kRightX, kFloorY, kBackZ};
  const Material brick = tiled(TextureId::Brick, 300);
  walls.materials[0] = tiled(TextureId::Brick, 300, {0.9f, 1.0f, 1.1f});  // left wall
  walls.materials[1] = tiled(TextureId::Brick, 300, {1.1f, 1.0f, 0.9f});  // right wall
  walls.materials[2] = tiled(TextureId::Noise, 200, {1.6f, 1.6f, 1.6f});  // ceiling
  walls.materials[3] = tiled(TextureId::Gravel, 400);                     // floor
  walls.materials[4] = brick;                                             // behind the robot
  walls.materials[5] = brick;                                             // back wall
  prims.push_back(walls);
  if (!furnished) return prims;

  const Material wood = tiled(TextureId::Wood, 400);
  const Material darkWood = tiled(TextureId::Wood, 300, {0.6f, 0.6f, 0.65f});
  const Material grass = tiled(TextureId::Grass, 500);
  prims.push_back(block(-2.1, -1.1, 2.3, 3.1, 0.75, wood));     // table
  prims.push_back(block(1.8, 2.6, 2.6, 3.6, 1.85, darkWood));   // cabinet
  prims.push_back(block(-0.9, 0.7, 4.55, 5.0, 2.1, wood));      // shelf on the back wall
  prims.push_back(block(0.45, 0.95, 3.4, 3.9, 0.5, grass));     // planter
  prims.push_back(block(1.05, 1.55, 1.7, 2.2, 0.9, wood));      // chair-high box
  prims.push_back(block(-2.6, -2.2, 0.8, 1.6, 1.1, darkWood));  // side cupboard
  // Posters: real photographs, skin-coloured ones and faces among them.
  prims.push_back(
      poster({-2.0, -0.75, kBackZ - 0.02}, {-1.2, 0.15, kBackZ}, TextureId::PosterA, 0.8));
  prims.push_back(
      poster({1.0, -0.8, kBackZ - 0.02}, {1.9, -0.24, kBackZ}, TextureId::PosterB, 0.9));
  prims.push_back(poster({kLeftX, -0.7, 2.6}, {kLeftX + 0.02, 0.0, 3.6}, TextureId::PosterC, 1.0));
  prims.push_back(poster({-0.7, -1.2, 4.53}, {0.5, -0.45, 4.55}, TextureId::PosterD, 1.2));
  if (skinClutter) {
    // Skin-toned clutter where a hand may pass in front of it: panels on the
    // back wall and the shelf at hand and head height, a rug under the
    // people, a panel on the left wall.
    const Material skin = tiled(TextureId::Noise, 250, {0.82f, 1.09f, 1.52f});
    const Material paler = tiled(TextureId::Noise, 250, {0.95f, 1.15f, 1.45f});
    prims.push_back(makeBox({-1.1, -0.5, kBackZ - 0.03}, {-0.2, 0.6, kBackZ}, skin));
    prims.push_back(makeBox({0.3, -0.2, kBackZ - 0.03}, {1.0, 0.9, kBackZ}, paler));
    prims.push_back(makeBox({-0.5, -0.1, 4.5}, {0.5, 0.5, 4.53}, skin));
    prims.push_back(makeBox({-0.9, kFloorY - 0.01, 0.9}, {0.9, kFloorY, 2.4}, paler));
    prims.push_back(makeBox({kLeftX, -0.3, 1.2}, {kLeftX + 0.02, 0.6, 2.4}, skin));
  }
  return prims;
}

}  // namespace horopter::synth::room
