// horopter_bench: registers the rows (their backends are only known at run
// time), then runs Google Benchmark as BENCHMARK_MAIN would.
#include <benchmark/benchmark.h>

#include <string_view>
#include <vector>

#include "registration.hpp"

namespace {

// The scalar reference takes about a second per 720p/d128 frame, so a short
// minimum time keeps the full run to a few minutes (slow rows run once). A
// --benchmark_min_time on the command line replaces it.
char kDefaultMinTime[] = "--benchmark_min_time=0.2";

std::vector<char*> withDefaults(int argc, char** argv) {
  std::vector<char*> args(argv, argv + argc);
  bool minTimeGiven = false;
  for (int i = 1; i < argc; ++i)
    minTimeGiven |= std::string_view(argv[i]).starts_with("--benchmark_min_time");
  if (!minTimeGiven) args.insert(args.begin() + 1, kDefaultMinTime);
  args.push_back(nullptr);  // argv is null-terminated
  return args;
}

}  // namespace

int main(int argc, char** argv) {
  horopter::bench::registerDisparityRows();
  horopter::bench::registerKernelRows();
  horopter::bench::registerFrontendRows();
  horopter::bench::registerZoneRows();

  std::vector<char*> args = withDefaults(argc, argv);
  int count = static_cast<int>(args.size()) - 1;
  benchmark::Initialize(&count, args.data());
  if (benchmark::ReportUnrecognizedArguments(count, args.data())) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
