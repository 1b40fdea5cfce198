// loadStereoCalibration on arbitrary bytes: a horopter::Error, never a crash,
// an OpenCV exception or undefined behaviour.
#include <cstddef>
#include <cstdint>
#include <cstdio>

#include "fuzz_file.hpp"
#include "horopter/core/error.hpp"
#include "horopter/vision/calibration.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = horopter::fuzz::scratchPath(".yml");
  horopter::fuzz::writeScratch(path, data, size);
  try {
    (void)horopter::loadStereoCalibration(path);
  } catch (const horopter::Error&) {
  }
  std::remove(path.c_str());
  return 0;
}
