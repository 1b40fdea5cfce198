// Independent, seeded trials run `jobs` at a time on threads of this process.
// Results come back in trial order, so they do not depend on `jobs`; only
// wall times do (the trials then compete for the cores).
#pragma once

#include <algorithm>
#include <atomic>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace horopter::eval {

// Calls run(i) for every i in [0, count); after each, done(i, result) under
// a lock, in order of completion. The first exception stops the other
// workers after their current trial and is rethrown once all have joined.
template <class Result>
std::vector<Result> runTrials(int count, int jobs, const std::function<Result(int)>& run,
                              const std::function<void(int, const Result&)>& done = {}) {
  std::vector<Result> results(static_cast<std::size_t>(std::max(0, count)));
  std::atomic<int> next{0};
  std::mutex lock;
  std::exception_ptr failure;
  const auto work = [&] {
    for (int i = next++; i < count; i = next++) {
      try {
        results[static_cast<std::size_t>(i)] = run(i);
        if (done) {
          const std::lock_guard guard(lock);
          done(i, results[static_cast<std::size_t>(i)]);
        }
      } catch (...) {
        const std::lock_guard guard(lock);
        if (!failure) failure = std::current_exception();
        next = count;  // the others stop after their trial
        return;
      }
    }
  };
  std::vector<std::thread> workers;
  for (int j = 1; j < std::min(jobs, count); ++j)
    workers.emplace_back(work);
  work();
  for (std::thread& w : workers)
    w.join();
  if (failure) std::rethrow_exception(failure);
  return results;
}

}  // namespace horopter::eval
