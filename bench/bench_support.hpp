// What every bench row shares: the settings grid, row-name pieces, counters
// and the measuring policy.
#pragma once

#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "horopter/core/image.hpp"
#include "horopter/kernels/backend.hpp"
#include "horopter/kernels/stereo_params.hpp"

namespace horopter::bench {

struct FrameSize {
  int width = 0;
  int height = 0;
};

// One point of the matching grid.
struct MatchSetting {
  FrameSize size;
  int numDisparities = 0;
  int blockSize = 0;
  PreFilterType preFilter = PreFilterType::XSobel;  // rows of another are tagged "/norm"
  int leftBand = 0;  // StereoParams::leftBand; rows with a band are tagged "/band<m>" last
};

inline constexpr FrameSize kSizes[] = {{320, 240}, {640, 480}, {1280, 720}};
inline constexpr int kDisparityCounts[] = {64, 128};
inline constexpr int kBlockSize = 9;
// Thread counts of the rows, ours (stripes on the front end's pool) and the
// peer's (cv::setNumThreads) alike. Rows with more than one thread time the
// wall clock (Google Benchmark appends "/real_time" to their names).
inline constexpr int kThreadCounts[] = {1, 2};

// Every size x disparity count at the standard block size; with
// `withTarget`, also the issue-3 target 1280x720/d128/w15 and
// 640x480/d64/w9 with StereoBM's normalized-response prefilter.
std::vector<MatchSetting> matchSettings(bool withTarget);
// The left band's settings (disparity/ rows only): 640x480 d64 w9 and the
// target, band 16.
std::vector<MatchSetting> bandSettings();

// The registered backends available on this machine, so that a new backend
// gets its rows without touching the benches.
std::vector<const Backend*> availableBackends();

// Row-name pieces: "640x480" and "d64/w9/t1" ("d64/w9/norm/t1" for the
// normalized-response prefilter, "d64/w9/t1/band16" with the left band).
std::string sizeTag(FrameSize size);
std::string matchTag(const MatchSetting& setting, int threads);

// The default parameters (cv::StereoBM's names and values) at this setting:
// what the front end runs.
StereoParams frontendParams(const MatchSetting& setting);
// The same with the speckle filter off: the post-processing that ours and
// the peer both run in the disparity/ and opencv_stereobm/ rows.
StereoParams matchParams(const MatchSetting& setting);

// "Mpix/s", and "Mpix*disp/s" for rows that search disparities.
void setPixelCounters(benchmark::State& state, FrameSize size);
void setPixelCounters(benchmark::State& state, const MatchSetting& setting);

// Milliseconds. Rows keep their plain names: the minimum time comes from
// the command line (main() sets a short default) rather than MinTime(),
// which Google Benchmark appends to the name.
benchmark::internal::Benchmark* measure(benchmark::internal::Benchmark* row);

// Copies the pixels of `src` into `dst` (same size and type), for the
// in-place kernels whose input must be restored before each run.
void copyPixels(const Image& src, Image& dst);

}  // namespace horopter::bench
