// Shared by the OpenCL tests: skip (visibly, with the reason) where this
// machine has no OpenCL device, unless HOROPTER_REQUIRE_BACKENDS names
// "opencl", where that is a failure.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "opencl/device.hpp"

namespace horopter::test {

inline bool openclRequired() {
  const char* env = std::getenv("HOROPTER_REQUIRE_BACKENDS");
  if (env == nullptr) return false;
  std::string list = ",";  // appended, not operator+ (GCC 12's -Wrestrict false positive)
  list += env;
  list += ",";
  return list.find(",opencl,") != std::string::npos;
}

#define HOROPTER_REQUIRE_OPENCL_DEVICE()                                                    \
  do {                                                                                      \
    if (::horopter::opencl::devices().empty()) {                                            \
      if (::horopter::test::openclRequired())                                               \
        FAIL() << "OpenCL is required (HOROPTER_REQUIRE_BACKENDS) but there is no device: " \
               << ::horopter::opencl::probeError();                                         \
      GTEST_SKIP() << "no OpenCL device here: " << ::horopter::opencl::probeError();        \
    }                                                                                       \
  } while (0)

}  // namespace horopter::test
