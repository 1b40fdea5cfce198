// The tiled matcher's tuning variants (kernels/opencl/tiled_variant.hpp):
// HOROPTER_OPENCL_TILED takes a variant's name or key=value pairs over the
// default, each variant builds with its own options (so its own program and
// program-cache entry), and a bad value is an error naming the variable.
// Needs no device.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "horopter/core/error.hpp"
#include "opencl/tiled_variant.hpp"
#include "scoped_env.hpp"

namespace horopter::test {
namespace {

TEST(TiledVariant, UnsetOrEmptyIsTheDefaultWithTheProgramsOwnOptions) {
  for (const char* value : {static_cast<const char*>(nullptr), ""}) {
    const ScopedEnv env("HOROPTER_OPENCL_TILED", value);
    const opencl::TiledVariant v = opencl::tiledVariant();
    EXPECT_EQ(v.name, "default");
    // Its block compiled in for that block size; the program's own
    // defaults for every other.
    EXPECT_EQ(v.forBlock(v.block).buildOptions(),
              " -DSAD_TILED_RADIUS=" + std::to_string(v.block / 2));
    EXPECT_EQ(v.forBlock(v.block + 2).buildOptions(), "");
  }
  EXPECT_EQ(opencl::tiledVariants().front().name, "default");
}

TEST(TiledVariant, EveryNamedVariantIsFoundAndBuildsWithItsOwnOptions) {
  std::set<std::string> variants;  // build options and work-group shape: each its own
  for (const opencl::TiledVariant& v : opencl::tiledVariants()) {
    const ScopedEnv env("HOROPTER_OPENCL_TILED", v.name.c_str());
    const opencl::TiledVariant got = opencl::tiledVariant();
    EXPECT_EQ(got.name, v.name);
    // Variants whose kernel parameters are the program's own defaults
    // build no options of their own (the shape is the launch's).
    const opencl::TiledVariant base;
    const bool sameKernel = v.passPlanes == base.passPlanes && v.spread == base.spread &&
                            v.split == base.split && v.rows == base.rows && v.block == 0;
    EXPECT_EQ(got.buildOptions().empty(), sameKernel) << v.name;
    const std::string key = got.buildOptions() + " @" + std::to_string(got.groupWidth) + "x" +
                            std::to_string(got.groupHeight);
    EXPECT_TRUE(variants.insert(key).second) << v.name << " is another's twin";
  }
}

TEST(TiledVariant, KeyValuePairsChangeTheDefault) {
  const opencl::TiledVariant v =
      opencl::parseTiledVariant("w=16,h=4,planes=3,spread=0,split=2,rows=3");
  EXPECT_EQ(v.groupWidth, 16);
  EXPECT_EQ(v.groupHeight, 4);
  EXPECT_EQ(v.passPlanes, 3);
  EXPECT_FALSE(v.spread);
  EXPECT_EQ(v.split, 2);
  EXPECT_EQ(v.rows, 3);
  EXPECT_EQ(v.forBlock(11).buildOptions(),
            " -DSAD_TILED_PASS_PLANES=3 -DSAD_TILED_SPREAD=0 -DSAD_TILED_SPLIT=2"
            " -DSAD_TILED_ROWS=3");
  // A block compiled in serves that block size; others take the rest.
  const opencl::TiledVariant b7 = opencl::parseTiledVariant("rows=2,block=7");
  EXPECT_EQ(b7.forBlock(7).buildOptions(), " -DSAD_TILED_ROWS=2 -DSAD_TILED_RADIUS=3");
  EXPECT_EQ(b7.forBlock(9).buildOptions(), " -DSAD_TILED_ROWS=2");
  EXPECT_EQ(opencl::parseTiledVariant("block=0").forBlock(9).buildOptions(), "");
  const opencl::TiledVariant wide = opencl::parseTiledVariant("w=64,h=4");
  EXPECT_EQ(wide.groupWidth, 64);
  EXPECT_EQ(wide.passPlanes, opencl::tiledVariants().front().passPlanes);
}

TEST(TiledVariant, AnyOtherValueIsAnErrorNamingTheVariable) {
  for (const char* value : {"fast", "Default", "w=0", "w=64,h=32", "planes=9", "rows=17", "block=8",
                            "depth=2", "w=", "w=4x", "w=32,,h=8"}) {
    SCOPED_TRACE(value);
    const ScopedEnv env("HOROPTER_OPENCL_TILED", value);
    try {
      opencl::tiledVariant();
      ADD_FAILURE() << "no error";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("HOROPTER_OPENCL_TILED='" + std::string(value) + "'"),
                std::string::npos)
          << e.what();
    }
  }
}

}  // namespace
}  // namespace horopter::test
