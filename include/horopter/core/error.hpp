// horopter::Error: the one exception type of the library.
#pragma once

#include "horopter/core/export.hpp"

#include <stdexcept>
#include <string>

namespace horopter {

// Thrown for every bad input or failed operation. The message names what was
// wrong and what to change ("blockSize must be odd, got 8: use 7 or 9").
class HOROPTER_API Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace horopter
