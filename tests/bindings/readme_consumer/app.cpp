// The program the README's find_package snippet builds in
// bindings.install_consumer: the snippet is copied from README.md into a
// CMakeLists.txt beside this file, as written, and built against the install
// tree alone. It sets no C++ standard of its own, so it compiles only if
// horopter::horopter carries C++20 (the public headers use std::span).
#include <horopter/vision/frontend.hpp>

#include <cstdint>
#include <cstdio>
#include <span>
#include <vector>

int main() {
  // A random-dot pair whose right view is the left one moved 4 px.
  constexpr int kWidth = 96, kHeight = 48, kShift = 4;
  std::vector<std::uint8_t> left(kWidth * kHeight), right(kWidth * kHeight);
  std::uint32_t state = 12345;
  for (auto& p : left) {
    state = state * 1664525u + 1013904223u;
    p = static_cast<std::uint8_t>(state >> 24);
  }
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      right[y * kWidth + x] = left[y * kWidth + (x + kShift < kWidth ? x + kShift : x)];

  horopter::StereoParams stereo;
  stereo.numDisparities = 16;
  stereo.blockSize = 5;
  horopter::StereoFrontend frontend(stereo, horopter::MedianParams{},
                                    horopter::findBackend("auto"));
  const horopter::Image& d = frontend.computeDisparity(
      horopter::makeView(left.data(), kWidth, kHeight, horopter::PixelType::U8C1),
      horopter::makeView(right.data(), kWidth, kHeight, horopter::PixelType::U8C1));
  const std::vector<std::int16_t> thresholds(kWidth, 16 * (kShift - 1));
  frontend.computeMask(std::span<const std::int16_t>(thresholds));
  const int centre = d.row<std::int16_t>(kHeight / 2)[kWidth / 2];
  const int inside = frontend.mask().row<std::uint8_t>(kHeight / 2)[kWidth / 2];
  std::printf("centre disparity %d/16 px, mask %d, on %s\n", centre, inside,
              frontend.backend().name.c_str());
  return centre == 16 * kShift && inside == 255 ? 0 : 1;
}
