// A fixed team of threads for loops over terms (their energies, gradients
// and Newton models; --num_threads).
//
// ParallelFor hands out chunks of consecutive indices to the team (the
// calling thread included) as they become free, so terms of unequal cost
// (an inertia term against a tetrahedron's eigensystem) balance. Which thread
// runs an index is not fixed; what a loop computes for an index must depend
// on the index alone, written to memory of that index, and any sum over
// indices is done afterwards in index order. Then every result is the same
// for any number of threads (the callers do so: core/incremental_potential.h,
// solver/projected_newton_solver.h, solver/newton_model_cache.h).
#pragma once

#include <atomic>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace ipstep {

class ThreadPool {
 public:
  // threads >= 1 (1: every loop runs on the calling thread).
  explicit ThreadPool(int threads);
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  int num_threads() const { return static_cast<int>(workers_.size()) + 1; }

  // body(begin, end, thread) for chunks [begin, end) covering [0, n), thread
  // in [0, num_threads()) naming the thread's scratch memory. Returns when
  // every chunk is done. Loops of fewer than `grain` indices per thread run
  // on the calling thread alone. body must not throw.
  using Body = std::function<void(int begin, int end, int thread)>;
  void ParallelFor(int n, int grain, const Body& body);

 private:
  void Work(int thread);
  void RunChunks(int thread);

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable start_;
  std::condition_variable done_;
  long generation_ = 0;
  bool stop_ = false;
  int busy_ = 0;
  // The current loop.
  const Body* body_ = nullptr;
  int n_ = 0;
  int chunk_ = 1;
  std::atomic<int> next_{0};
};

// The default team size: the machine's hardware threads (at least 1).
int DefaultThreadCount();

}  // namespace ipstep
