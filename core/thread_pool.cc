#include "core/thread_pool.h"

#include <algorithm>

namespace ipstep {

ThreadPool::ThreadPool(int threads) {
  for (int t = 1; t < std::max(1, threads); ++t) workers_.emplace_back([this, t] { Work(t); });
}

ThreadPool::~ThreadPool() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  start_.notify_all();
  for (std::thread& worker : workers_) worker.join();
}

void ThreadPool::RunChunks(int thread) {
  while (true) {
    const int begin = next_.fetch_add(chunk_);
    if (begin >= n_) return;
    (*body_)(begin, std::min(n_, begin + chunk_), thread);
  }
}

void ThreadPool::Work(int thread) {
  long seen = 0;
  while (true) {
    {
      std::unique_lock<std::mutex> lock(mutex_);
      start_.wait(lock, [&] { return stop_ || generation_ != seen; });
      if (stop_) return;
      seen = generation_;
    }
    RunChunks(thread);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (--busy_ == 0) done_.notify_one();
    }
  }
}

void ThreadPool::ParallelFor(int n, int grain, const Body& body) {
  if (n <= 0) return;
  const int threads = num_threads();
  if (threads == 1 || n < 2 * std::max(1, grain)) {
    body(0, n, 0);
    return;
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    body_ = &body;
    n_ = n;
    // About 16 chunks per thread: small enough to balance, large enough
    // that the shared counter is not contended.
    chunk_ = std::max(1, n / (16 * threads));
    next_.store(0);
    busy_ = threads - 1;
    ++generation_;
  }
  start_.notify_all();
  RunChunks(0);
  std::unique_lock<std::mutex> lock(mutex_);
  done_.wait(lock, [&] { return busy_ == 0; });
  body_ = nullptr;
}

int DefaultThreadCount() { return std::max(1u, std::thread::hardware_concurrency()); }

}  // namespace ipstep
