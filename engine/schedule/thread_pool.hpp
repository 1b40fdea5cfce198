// A fixed pool of worker threads for splitting one frame's kernels into
// stripes. The calling thread works too, so a pool of N threads starts N - 1
// workers and a pool of 1 starts none.
//
// A frame's kernels come as batches back to back (prefilter, match,
// left-right check, ...), some a tenth of a millisecond long, while waking a
// thread blocked on a condition variable takes tens of microseconds. So a
// worker that runs out of tasks, and the caller waiting for the batch's end,
// poll for up to kSpinMicroseconds before they block (as OpenCV's and TBB's
// pools do). On 2 cores, ratio to cv::StereoBM at two threads (4 alternating
// runs): 640x480/d64/w9 4.80 -> 5.44, 1280x720/d128/w15 3.44 -> 3.52; 50 us
// gave 5.34 and 3.48.
#pragma once

#include <atomic>
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

  // How long an idle thread polls for work, or the caller for the batch's
  // end, before it blocks.
  static constexpr int kSpinMicroseconds = 200;

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
  // Mirrors of generation_ and of "finished_ == count_" for the polls, which
  // do not take the mutex.
  std::atomic<unsigned> published_{0};
  std::atomic<bool> batchDone_{true};
  std::exception_ptr error_;
};

}  // namespace horopter
