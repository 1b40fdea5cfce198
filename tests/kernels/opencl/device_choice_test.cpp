// Choosing an OpenCL device by name: "opencl", "opencl:N", a part of the
// device's name; bad names are clear errors.
#include <gtest/gtest.h>

#include <string>

#include "horopter/core/error.hpp"
#include "horopter/kernels/backend.hpp"
#include "opencl/device.hpp"
#include "opencl_support.hpp"

namespace horopter::test {
namespace {

std::string errorOf(const std::string& name) {
  try {
    findBackend(name);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(OpenClDeviceChoice, OpenClIsRegisteredWithOrWithoutADevice) {
  bool found = false;
  for (const Backend* b : registeredBackends()) {
    if (b->name != "opencl") continue;
    found = true;
    if (!b->available) {
      EXPECT_FALSE(b->unavailableReason.empty());
    }
  }
  EXPECT_TRUE(found);
}

TEST(OpenClDeviceChoice, DefaultIndexAndNameSubstringPickTheSameBackend) {
  HOROPTER_REQUIRE_OPENCL_DEVICE();
  const Backend& byDefault = findBackend("opencl");
  EXPECT_TRUE(byDefault.available);
  EXPECT_EQ(byDefault.name, "opencl");
  // Every device is reachable by its index, and the default by its own.
  for (const opencl::Device* d : opencl::devices()) {
    std::string index = "opencl:";  // appended, not operator+ (GCC 12's -Wrestrict false positive)
    index += std::to_string(d->desc().index);
    const Backend& byIndex = findBackend(index);
    EXPECT_NE(byIndex.description.find(d->desc().name), std::string::npos) << index;
  }
  // A distinctive part of the first device's name, in another case.
  const opencl::Device* first = opencl::devices().front();
  std::string part =
      first->desc().name.substr(0, std::min<std::size_t>(6, first->desc().name.size()));
  for (char& c : part)
    c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  const Backend& byName = findBackend(part);
  EXPECT_NE(byName.description.find(first->desc().name), std::string::npos);
}

TEST(OpenClDeviceChoice, BadNamesAreClearErrors) {
  const std::string outOfRange = errorOf("opencl:99");
  EXPECT_NE(outOfRange.find("no OpenCL device 'opencl:99'"), std::string::npos) << outOfRange;
  EXPECT_NE(errorOf("opencl:x").find("no OpenCL device"), std::string::npos);
  const std::string unknown = errorOf("no-such-device-anywhere");
  EXPECT_NE(unknown.find("unknown backend 'no-such-device-anywhere'"), std::string::npos)
      << unknown;
  EXPECT_NE(unknown.find("opencl:N"), std::string::npos) << unknown;
}

}  // namespace
}  // namespace horopter::test
