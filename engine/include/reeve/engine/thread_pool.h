// A small fixed pool of threads that runs the indices of one task at a time
// (issue 30: scenes stepped side by side; later, islands). Work is handed
// out index by index, so a slow item does not hold up a thread's share;
// what each index computes must not depend on which thread runs it.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace reeve {

class ThreadPool {
 public:
  /// `threads` >= 1 in all, the caller of run() included: threads - 1
  /// workers are started. std::invalid_argument below 1.
  explicit ThreadPool(int threads);
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  int threads() const { return static_cast<int>(workers_.size()) + 1; }

  /// Runs task(i) once for each i in [0, n), on the pool's threads and the
  /// caller's, and returns when all have returned. An exception a task
  /// throws is rethrown here (the first one; the other indices still run).
  /// Not reentrant: one run() at a time per pool.
  void run(int n, const std::function<void(int)>& task);

  /// The cores this machine offers (std::thread::hardware_concurrency),
  /// at least 1.
  static int cores();

 private:
  void work();  // a worker's loop
  /// Runs indices of the current task until none is left to hand out;
  /// `lock` holds mutex_ on entry and exit, not while a task runs.
  void drain(std::unique_lock<std::mutex>& lock);
  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable wake_, done_;
  const std::function<void(int)>* task_ = nullptr;
  int n_ = 0, next_ = 0, running_ = 0;  // indices, the next to hand out, workers inside drain()
  std::uint64_t generation_ = 0;        // one per run(): wakes the workers
  bool stop_ = false;
  std::exception_ptr error_;
};

}  // namespace reeve
