// The on-disk program cache: a first build writes the entry, the next one
// loads it, and a corrupt, truncated or stale entry is rebuilt (never
// trusted), after which the kernels still give the reference's results.
#include <gtest/gtest.h>
#include <stdlib.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "horopter/kernels/kernels.hpp"
#include "opencl/device.hpp"
#include "opencl/launch.hpp"
#include "opencl/program_cache.hpp"
#include "opencl_support.hpp"
#include "test_support.hpp"

namespace horopter::test {
namespace {

namespace fs = std::filesystem;

// Points XDG_CACHE_HOME at a fresh directory for the test's lifetime.
class CacheDir {
 public:
  CacheDir() {
    path_ = fs::temp_directory_path() /
            ("horopter-cl-cache-test-" + std::to_string(::getpid()) + "-" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(path_);
    fs::create_directories(path_);
    const char* old = std::getenv("XDG_CACHE_HOME");
    hadOld_ = old != nullptr;
    if (hadOld_) old_ = old;
    ::setenv("XDG_CACHE_HOME", path_.c_str(), 1);
  }
  ~CacheDir() {
    if (hadOld_)
      ::setenv("XDG_CACHE_HOME", old_.c_str(), 1);
    else
      ::unsetenv("XDG_CACHE_HOME");
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  CacheDir(const CacheDir&) = delete;
  CacheDir& operator=(const CacheDir&) = delete;

 private:
  fs::path path_;
  std::string old_;
  bool hadOld_ = false;
};

struct Program {
  explicit Program(opencl::BuiltProgram b) : built(b) {}
  ~Program() {
    if (built.program) clReleaseProgram(built.program);
  }
  Program(const Program&) = delete;
  Program& operator=(const Program&) = delete;
  opencl::BuiltProgram built;
};

// Runs the prefilter of `program` on a random image and compares it with the
// scalar reference.
void expectPrefilterMatchesReference(opencl::Device& device, cl_program program) {
  const int w = 97, h = 13, cap = 31;
  const TestImage src = randomImage(w, h, PixelType::U8C1, 5, 0, 255);
  TestImage ref(w, h, PixelType::U8C1), refTexture(w, h, PixelType::U8C1);
  prefilterXSobel(src.view(), cap, ref.view(), refTexture.view(), scalarBackend());

  cl_int err = CL_SUCCESS;
  cl_kernel kernel = clCreateKernel(program, "prefilter_xsobel", &err);
  ASSERT_EQ(err, CL_SUCCESS) << opencl::errorName(err);
  cl_command_queue q = opencl::createQueue(device);
  opencl::Buffer in, out, tex;
  cl_context ctx = device.context();
  opencl::writeRows(q, in.get(ctx, w * h), src.view(), 0, h, true, nullptr);
  opencl::enqueuePrefilter(q, kernel, in.get(ctx, w * h), w, h, cap, {0, h}, out.get(ctx, w * h),
                           tex.get(ctx, w * h), true, true, nullptr);
  TestImage got(w, h, PixelType::U8C1), gotTexture(w, h, PixelType::U8C1);
  opencl::readRows(q, out.get(ctx, w * h), got.view(), 0, h, true, nullptr);
  opencl::readRows(q, tex.get(ctx, w * h), gotTexture.view(), 0, h, true, nullptr);
  clReleaseCommandQueue(q);
  clReleaseKernel(kernel);
  EXPECT_TRUE(sameImage(ref.view(), got.view()));
  EXPECT_TRUE(sameImage(refTexture.view(), gotTexture.view()));
}

void overwrite(const std::string& path, const std::string& bytes, std::streamoff at = 0,
               bool truncate = false) {
  if (truncate) {
    fs::resize_file(path, static_cast<std::uintmax_t>(at));
    return;
  }
  std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
  ASSERT_TRUE(f.good()) << path;
  f.seekp(at);
  f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

TEST(OpenClProgramCache, WritesLoadsAndRebuildsBadEntries) {
  HOROPTER_REQUIRE_OPENCL_DEVICE();
  const CacheDir dir;
  opencl::Device& device = *opencl::devices().front();
  const opencl::DeviceDesc& desc = device.desc();
  cl_context ctx = device.context();

  std::string file;
  {
    const Program first(opencl::buildProgram(desc, ctx));
    EXPECT_EQ(first.built.origin, opencl::ProgramOrigin::Source);
    file = first.built.cacheFile;
    ASSERT_FALSE(file.empty());
    ASSERT_TRUE(fs::exists(file)) << file;
  }
  {
    const Program loaded(opencl::buildProgram(desc, ctx));
    EXPECT_EQ(loaded.built.origin, opencl::ProgramOrigin::DiskCache);
    expectPrefilterMatchesReference(device, loaded.built.program);
  }
  const auto size = static_cast<std::streamoff>(fs::file_size(file));
  struct Damage {
    const char* what;
    std::streamoff at;
    bool truncate;
  };
  // Garbage over the whole header, a flipped byte in the key (a stale entry:
  // another device, driver or source), garbage inside the binary, a cut.
  const Damage damages[] = {{"garbage header", 0, false},
                            {"stale key", 40, false},
                            {"garbage binary", size - 64, false},
                            {"truncated", size / 2, true}};
  for (const Damage& damage : damages) {
    SCOPED_TRACE(damage.what);
    overwrite(file, std::string(16, '\x5a'), damage.at, damage.truncate);
    {
      const Program rebuilt(opencl::buildProgram(desc, ctx));
      EXPECT_EQ(rebuilt.built.origin, opencl::ProgramOrigin::RebuiltAfterBadCacheEntry);
      expectPrefilterMatchesReference(device, rebuilt.built.program);
    }
    const Program again(opencl::buildProgram(desc, ctx));
    EXPECT_EQ(again.built.origin, opencl::ProgramOrigin::DiskCache)
        << "the entry was not rewritten";
  }
}

TEST(OpenClProgramCache, CanBeTurnedOff) {
  HOROPTER_REQUIRE_OPENCL_DEVICE();
  const CacheDir dir;
  ::setenv("HOROPTER_OPENCL_CACHE", "0", 1);
  EXPECT_EQ(opencl::cacheDirectory(), "");
  ::unsetenv("HOROPTER_OPENCL_CACHE");
  EXPECT_NE(opencl::cacheDirectory().find("horopter"), std::string::npos);
}

}  // namespace
}  // namespace horopter::test
