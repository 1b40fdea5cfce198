// readBodyTrack on arbitrary bytes, truth column requested.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <vector>

#include "fuzz_file.hpp"
#include "horopter/core/error.hpp"
#include "horopter/movement/body_track_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = horopter::fuzz::scratchPath(".csv");
  horopter::fuzz::writeScratch(path, data, size);
  try {
    std::vector<horopter::MovementClass> truth;
    (void)horopter::readBodyTrack(path, &truth);
  } catch (const horopter::Error&) {
  }
  std::remove(path.c_str());
  return 0;
}
