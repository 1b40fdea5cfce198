// A fixed pool of worker threads for splitting one frame's kernels into
// stripes. The calling thread works too, so a pool of N threads starts N - 1
// workers and a pool of 1 starts none.
#pragma once

#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

namespace horopter {

class ThreadPool {
 public:
  // threads >= 1; throws horopter::Error otherwise or above 256.
  explicit ThreadPool(int threads);
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  int threads() const { return static_cast<int>(workers_.size()) + 1; }

  // Runs task(0) .. task(count - 1), spread over the pool and the caller, and
  // returns when all are done. The first exception a task throws is rethrown
  // here (after every task has finished). Not reentrant: one call at a time.
  void run(int count, const std::function<void(int)>& task);

 private:
  void workerLoop();
  void drain();  // takes and runs tasks of the current batch until none is left

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::condition_variable done_;
  const std::function<void(int)>* task_ = nullptr;
  int count_ = 0;
  int next_ = 0;
  int finished_ = 0;
  unsigned generation_ = 0;
  bool stopping_ = false;
  std::exception_ptr error_;
};

}  // namespace horopter
