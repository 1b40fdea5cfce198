// Dropping a PNG's colour profile, which libpng warns about (readImage in
// image_files.hpp uses it).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace horopter {

// `bytes` without the chunks named iCCP when they are a PNG file; any other
// bytes (not a PNG, a truncated chunk) come back unchanged. An iCCP chunk is
// an embedded ICC colour profile, which OpenCV does not apply: dropping it
// leaves every decoded pixel the same.
std::vector<std::uint8_t> withoutIccpChunks(std::vector<std::uint8_t> bytes);

}  // namespace horopter
