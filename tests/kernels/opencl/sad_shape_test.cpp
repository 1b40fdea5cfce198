// The SAD matcher's shape (kernels/opencl/launch.hpp): HOROPTER_OPENCL_SAD
// picks strip or tiled, auto (or unset) takes tiled on a GPU only, and any
// other value is an error that names the variable. Needs no device.
#include <gtest/gtest.h>

#include <string>

#include "horopter/core/error.hpp"
#include "opencl/launch.hpp"
#include "scoped_env.hpp"

namespace horopter::test {
namespace {

opencl::DeviceDesc deviceOfType(bool gpu) {
  opencl::DeviceDesc d;
  d.gpu = gpu;
  return d;
}

TEST(SadShape, AutoTakesTiledOnAGpuOnly) {
  for (const char* value : {static_cast<const char*>(nullptr), "", "auto"}) {
    SCOPED_TRACE(value ? value : "(unset)");
    const ScopedEnv env("HOROPTER_OPENCL_SAD", value);
    EXPECT_EQ(opencl::sadShape(deviceOfType(true)), opencl::SadShape::Tiled);
    EXPECT_EQ(opencl::sadShape(deviceOfType(false)), opencl::SadShape::Strip);
  }
}

TEST(SadShape, TheVariableForcesEitherShapeOnAnyDevice) {
  for (const bool gpu : {false, true}) {
    {
      const ScopedEnv env("HOROPTER_OPENCL_SAD", "strip");
      EXPECT_EQ(opencl::sadShape(deviceOfType(gpu)), opencl::SadShape::Strip);
    }
    const ScopedEnv env("HOROPTER_OPENCL_SAD", "tiled");
    EXPECT_EQ(opencl::sadShape(deviceOfType(gpu)), opencl::SadShape::Tiled);
  }
  EXPECT_STREQ(opencl::sadShapeName(opencl::SadShape::Strip), "strip");
  EXPECT_STREQ(opencl::sadShapeName(opencl::SadShape::Tiled), "tiled");
}

TEST(SadShape, AnyOtherValueIsAnErrorNamingTheVariable) {
  for (const char* value : {"Tiled", "gpu", "strip "}) {
    SCOPED_TRACE(value);
    const ScopedEnv env("HOROPTER_OPENCL_SAD", value);
    try {
      opencl::sadShape(deviceOfType(true));
      ADD_FAILURE() << "no error";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("HOROPTER_OPENCL_SAD='" + std::string(value) + "'"),
                std::string::npos)
          << e.what();
    }
  }
}

}  // namespace
}  // namespace horopter::test
