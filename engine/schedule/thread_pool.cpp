#include "schedule/thread_pool.hpp"

#include <chrono>
#include <string>

#include "horopter/core/error.hpp"

namespace horopter {

namespace {

// Polls `ready` for up to ThreadPool::kSpinMicroseconds; true once it holds.
template <typename Ready>
bool pollFor(const Ready& ready) {
  using Clock = std::chrono::steady_clock;
  const auto until = Clock::now() + std::chrono::microseconds(ThreadPool::kSpinMicroseconds);
  for (;;) {
    for (int i = 0; i < 64; ++i) {
      if (ready()) return true;
#if defined(__x86_64__) || defined(__i386__)
      __builtin_ia32_pause();
#endif
    }
    if (Clock::now() >= until) return ready();
  }
}

}  // namespace

ThreadPool::ThreadPool(int threads) {
  if (threads < 1 || threads > 256)
    throw Error("thread count must be within 1..256, got " + std::to_string(threads));
  workers_.reserve(static_cast<std::size_t>(threads - 1));
  for (int i = 1; i < threads; ++i)
    workers_.emplace_back([this] { workerLoop(); });
}

ThreadPool::~ThreadPool() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  for (auto& w : workers_)
    w.join();
}

void ThreadPool::drain() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (task_ != nullptr && next_ < count_) {
    const int index = next_++;
    const auto* task = task_;
    lock.unlock();
    try {
      (*task)(index);
    } catch (...) {
      std::lock_guard<std::mutex> errorLock(mutex_);
      if (!error_) error_ = std::current_exception();
    }
    lock.lock();
    if (++finished_ == count_) {
      batchDone_.store(true, std::memory_order_release);
      done_.notify_all();
    }
  }
}

void ThreadPool::workerLoop() {
  unsigned seen = 0;
  for (;;) {
    pollFor([&] { return published_.load(std::memory_order_acquire) != seen; });
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [&] { return stopping_ || generation_ != seen; });
      if (stopping_) return;
      seen = generation_;
    }
    drain();
  }
}

void ThreadPool::run(int count, const std::function<void(int)>& task) {
  if (count <= 0) return;
  if (workers_.empty() || count == 1) {
    for (int i = 0; i < count; ++i)
      task(i);
    return;
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    task_ = &task;
    count_ = count;
    next_ = 0;
    finished_ = 0;
    error_ = nullptr;
    ++generation_;
    batchDone_.store(false, std::memory_order_relaxed);
    published_.store(generation_, std::memory_order_release);
  }
  wake_.notify_all();
  drain();
  pollFor([&] { return batchDone_.load(std::memory_order_acquire); });
  std::unique_lock<std::mutex> lock(mutex_);
  done_.wait(lock, [&] { return finished_ == count_; });
  task_ = nullptr;
  if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
}

}  // namespace horopter
