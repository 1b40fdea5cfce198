// Stripes and threads: any thread count, and any split of a frame into row
// ranges, gives the one-thread, whole-frame result bit for bit, on every
// available backend. And the thread pool itself: every task runs once,
// errors reach the caller.
#include <atomic>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "horopter/core/error.hpp"
#include "horopter/kernels/kernels.hpp"
#include "horopter/vision/frontend.hpp"
#include "horopter/vision/geometry.hpp"
#include "schedule/thread_pool.hpp"
#include "test_support.hpp"

namespace horopter::test {
namespace {

TEST(ThreadPool, RunsEveryTaskOnceForAnyThreadCount) {
  for (int threads : {1, 2, 3, 8}) {
    ThreadPool pool(threads);
    for (int count : {0, 1, 2, 7, 100}) {
      std::vector<std::atomic<int>> hits(static_cast<std::size_t>(count));
      pool.run(count, [&](int i) { hits[static_cast<std::size_t>(i)]++; });
      for (int i = 0; i < count; ++i)
        EXPECT_EQ(hits[static_cast<std::size_t>(i)].load(), 1)
            << "task " << i << " of " << count << " with " << threads << " threads";
    }
  }
}

TEST(ThreadPool, RethrowsATaskErrorAfterEveryTaskFinished) {
  ThreadPool pool(3);
  std::atomic<int> finished{0};
  EXPECT_THROW(pool.run(10,
                        [&](int i) {
                          finished++;
                          if (i == 4) throw std::runtime_error("task 4 failed");
                        }),
               std::runtime_error);
  EXPECT_EQ(finished.load(), 10);
  // The pool stays usable.
  std::atomic<int> again{0};
  pool.run(5, [&](int) { again++; });
  EXPECT_EQ(again.load(), 5);
}

// Batches back to back, as a frame's kernels come: the workers and the
// caller poll between them instead of blocking (ThreadPool::kSpinMicroseconds).
TEST(ThreadPool, RunsEveryTaskOfManyShortBatchesOnce) {
  ThreadPool pool(3);
  std::vector<std::atomic<int>> hits(7);
  for (int batch = 1; batch <= 2000; ++batch) {
    pool.run(7, [&](int i) { hits[static_cast<std::size_t>(i)]++; });
    for (int i = 0; i < 7; ++i)
      ASSERT_EQ(hits[static_cast<std::size_t>(i)].load(), batch) << "task " << i;
  }
}

// A pool destroyed while its workers still poll for the next batch, and one
// destroyed before it ran any: both join (a hang fails the test's timeout).
TEST(ThreadPool, JoinsItsWorkersWhileTheyPoll) {
  for (int round = 0; round < 50; ++round) {
    ThreadPool pool(2);
    if (round % 2 == 0) {
      std::atomic<int> ran{0};
      pool.run(2, [&](int) { ran++; });
      EXPECT_EQ(ran.load(), 2);
    }
  }
}

TEST(ThreadPool, RejectsAbsurdThreadCounts) {
  EXPECT_THROW(ThreadPool(0), Error);
  EXPECT_THROW(ThreadPool(-2), Error);
  EXPECT_THROW(ThreadPool(100000), Error);
}

class PerBackend : public ::testing::TestWithParam<const Backend*> {};

TEST_P(PerBackend, AnyThreadCountGivesTheOneThreadResult) {
  const Backend& backend = *GetParam();
  const StereoPair pair = stepScenePair(157, 61, {60, 110, 15, 45, 20, 6}, 11);
  StereoParams p;
  p.numDisparities = 32;
  p.blockSize = 7;
  RectifiedGeometry geometry{157.0, 78.0, 1.0};
  const auto thresholds =
      horopterThresholds(geometry, 157, fixationFromDisparity(geometry, 78.0, 12.0));

  StereoFrontend one(p, MedianParams{}, backend, 1);
  one.computeDisparity(pair.left.view(), pair.right.view());
  one.computeMask(thresholds, pair.left.view());
  for (int threads : {2, 3, 5, 61, 64}) {
    StereoFrontend many(p, MedianParams{}, backend, threads);
    many.computeDisparity(pair.left.view(), pair.right.view());
    many.computeMask(thresholds, pair.left.view());
    SCOPED_TRACE(backend.name + ", " + std::to_string(threads) + " threads");
    EXPECT_TRUE(sameImage(one.cleanedDisparity().view(), many.cleanedDisparity().view()));
    EXPECT_TRUE(sameImage(one.disparity().view(), many.disparity().view()));
    EXPECT_TRUE(sameImage(one.mask().view(), many.mask().view()));
    EXPECT_TRUE(sameImage(one.segmented().view(), many.segmented().view()));
  }
}

// Each row-local kernel run as uneven stripes (including empty and one-row
// stripes) equals the whole-frame call.
TEST_P(PerBackend, StripesOfRowsEqualTheWholeFrame) {
  const Backend& backend = *GetParam();
  const int w = 97, h = 40;
  const std::vector<RowRange> stripes = {{0, 0}, {0, 3}, {3, 4}, {4, 21}, {21, 21}, {21, 40}};
  StereoParams p;
  p.numDisparities = 32;
  p.blockSize = 5;
  p.minDisparity = -3;
  const TestImage left = randomImage(w, h, PixelType::U8C1, 5, 0, 255);
  const TestImage right = randomImage(w, h, PixelType::U8C1, 6, 0, 255);
  const int cap = p.preFilterCap;

  TestImage wholeF(w, h, PixelType::U8C1), wholeT(w, h, PixelType::U8C1);
  prefilterXSobel(left.view(), cap, wholeF.view(), wholeT.view(), backend);
  TestImage partF(w, h, PixelType::U8C1), partT(w, h, PixelType::U8C1);
  for (RowRange r : stripes)
    prefilterXSobel(left.view(), cap, partF.view(), partT.view(), backend, r);
  EXPECT_TRUE(sameImage(wholeF.view(), partF.view())) << "prefilter";
  EXPECT_TRUE(sameImage(wholeT.view(), partT.view())) << "texture";

  TestImage wholeD(w, h, PixelType::S16C1), wholeW(w, h, PixelType::S16C1);
  matchBlocks(wholeF.view(), right.view(), wholeT.view(), p, wholeD.view(), wholeW.view(), backend);
  TestImage partD(w, h, PixelType::S16C1), partW(w, h, PixelType::S16C1);
  for (RowRange r : stripes)
    matchBlocks(wholeF.view(), right.view(), wholeT.view(), p, partD.view(), partW.view(), backend,
                r);
  EXPECT_TRUE(sameImage(wholeD.view(), partD.view())) << "matching";
  EXPECT_TRUE(sameImage(wholeW.view(), partW.view())) << "right winner";

  leftRightCheck(wholeD.view(), wholeW.view(), p, backend);
  for (RowRange r : stripes)
    leftRightCheck(partD.view(), partW.view(), p, backend, r);
  EXPECT_TRUE(sameImage(wholeD.view(), partD.view())) << "left-right check";

  for (int k : {3, 5}) {
    MedianParams m;
    m.kernelSize = k;
    TestImage whole(w, h, PixelType::S16C1), part(w, h, PixelType::S16C1);
    medianFilter(wholeD.view(), whole.view(), m, invalidDisparity(p), backend);
    for (RowRange r : stripes)
      medianFilter(wholeD.view(), part.view(), m, invalidDisparity(p), backend, r);
    EXPECT_TRUE(sameImage(whole.view(), part.view())) << "median " << k;
  }

  std::vector<std::int16_t> thresholds(w);
  for (int x = 0; x < w; ++x)
    thresholds[x] = static_cast<std::int16_t>(16 * (x % 29));
  TestImage wholeM(w, h, PixelType::U8C1), wholeS(w, h, PixelType::U8C1);
  horopterMask(wholeD.view(), thresholds, invalidDisparity(p), wholeM.view(), left.view(),
               wholeS.view(), backend);
  TestImage partM(w, h, PixelType::U8C1), partS(w, h, PixelType::U8C1);
  for (RowRange r : stripes)
    horopterMask(wholeD.view(), thresholds, invalidDisparity(p), partM.view(), left.view(),
                 partS.view(), backend, r);
  EXPECT_TRUE(sameImage(wholeM.view(), partM.view())) << "mask";
  EXPECT_TRUE(sameImage(wholeS.view(), partS.view())) << "segmented";
}

std::vector<const Backend*> availableBackends() {
  std::vector<const Backend*> out;
  for (const Backend* b : registeredBackends())
    if (b->available) out.push_back(b);
  return out;
}

INSTANTIATE_TEST_SUITE_P(Available, PerBackend, ::testing::ValuesIn(availableBackends()),
                         [](const ::testing::TestParamInfo<const Backend*>& param) {
                           return param.param->name;
                         });

TEST(RowRange, OutsideTheImageIsAClearError) {
  const TestImage src = randomImage(20, 10, PixelType::U8C1, 1, 0, 255);
  TestImage out(20, 10, PixelType::U8C1);
  for (RowRange bad : {RowRange{-1, 3}, RowRange{5, 4}, RowRange{0, 11}}) {
    try {
      prefilterXSobel(src.view(), 31, out.view(), {}, scalarBackend(), bad);
      ADD_FAILURE() << "row range [" << bad.begin << ", " << bad.end << ") was accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("row range"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace horopter::test
