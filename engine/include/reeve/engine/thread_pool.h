// A small fixed pool of threads that runs the indices of one task at a time
// (issue 30: scenes stepped side by side, and a World's islands). Work is
// handed out index by index, so a slow item does not hold up a thread's
// share; what each index computes must not depend on which thread runs it.
#pragma once

#include <atomic>
#include <chrono>
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

  /// How long a worker that finished a run keeps looking for the next one
  /// before it sleeps, and the caller of run() for the workers to finish
  /// before it sleeps. A wake through the condition variable costs 20 to
  /// 30 us on a 2-core VM (DESIGN.md), more than a World's island solve of
  /// a substep may take; a spinning thread starts within a microsecond.
  /// 0 (the default) sleeps at once: right for runs far apart, as a
  /// batch's frames are. May be called while the workers run or wait.
  void setSpin(std::chrono::microseconds spin) { spin_us_.store(spin.count(), std::memory_order_relaxed); }

  /// Runs task(i) once for each i in [0, n), on the pool's threads and the
  /// caller's, and returns when all have returned. An exception a task
  /// throws is rethrown here (the first one; the other indices still run).
  /// Not reentrant: one run() at a time per pool. Allocates nothing.
  template <class Task>
  void run(int n, const Task& task) {
    runIndices(n, [](const void* t, int i) { (*static_cast<const Task*>(t))(i); }, &task, false);
  }

  /// Runs task(t) once for each thread t in [0, threads()): 0 on the
  /// caller's, t on worker t, every time. For work that should stay where
  /// its data is (a World's islands, substep after substep): handed out
  /// index by index, an island's bodies and solver moved between the cores'
  /// caches every substep, and two threads were slower than one.
  template <class Task>
  void runEach(const Task& task) {
    runIndices(threads(), [](const void* t, int i) { (*static_cast<const Task*>(t))(i); }, &task, true);
  }

  /// The cores this process may run on (its CPU affinity: taskset, a
  /// container's cpuset; the machine's, std::thread::hardware_concurrency,
  /// where that cannot be read), at least 1.
  static int cores();

 private:
  using Call = void (*)(const void* task, int i);
  /// `each`: index t runs on thread t (runEach), else where it is taken.
  void runIndices(int n, Call call, const void* task, bool each);
  void work(int id);  // worker id's loop (1 .. threads() - 1)
  /// Runs indices of run `generation` until none is left to take. Indices
  /// are taken by compare-and-swap on ticket_, with no lock: a thread that
  /// sleeps on a contended mutex wakes 20 to 30 us later, longer than a
  /// run of islands takes.
  void take(std::uint32_t generation);
  /// Runs index i of a run of n, and counts it done.
  void runOne(int i, int n);
  /// Spins for up to spin_us_ while `busy()`.
  template <class Busy>
  void spinWhile(const Busy& busy) const;

  std::vector<std::thread> workers_;
  // For the sleepers and error_. A run takes it only where a thread sleeps
  // or a task threw: taken every run, the worker's notify and the caller's
  // check of error_ met on it, and the loser slept in the kernel (a futex
  // each way, about 5 us a run on a 2-core VM, DESIGN.md).
  std::mutex mutex_;
  std::condition_variable wake_, finished_;
  // Who may be asleep, and whether error_ holds something. Each is read,
  // and the state it guards (the ticket, done_) written, in the opposite
  // order on the other side, all sequentially consistent: one of the two
  // sees the other's write, so no wake is lost.
  std::atomic<int> sleepers_{0};         // workers waiting on wake_
  std::atomic<bool> caller_waits_{false};  // the caller waiting on finished_
  std::atomic<bool> failed_{false};        // error_ is set
  std::atomic<std::uint64_t> ticket_{0};  // the run's generation << 32 | the next index to take (or runEach's mark)
  std::atomic<Call> call_{nullptr};
  std::atomic<const void*> task_{nullptr};
  std::atomic<int> n_{0};     // indices of the run
  std::atomic<int> done_{0};  // indices of the run finished
  std::uint32_t generation_ = 0;  // the caller's count of runs
  std::atomic<bool> stop_{false};
  std::atomic<std::chrono::microseconds::rep> spin_us_{0};  // setSpin: read by the workers as they run
  std::exception_ptr error_;
};

}  // namespace reeve
