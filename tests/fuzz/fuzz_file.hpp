// The fuzz targets' scratch file: the loaders under test take a path, so the
// input is written to one file per process (in $TMPDIR) and read back.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <string>

namespace horopter::fuzz {

inline std::string scratchPath(const char* suffix) {
  const char* tmp = std::getenv("TMPDIR");
  return std::string(tmp && *tmp ? tmp : "/tmp") + "/horopter-fuzz-" + std::to_string(getpid()) +
         suffix;
}

inline void writeScratch(const std::string& path, const std::uint8_t* data, std::size_t size) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
}

}  // namespace horopter::fuzz
