#include "reeve/engine/thread_pool.h"

#ifdef __linux__
#include <sched.h>
#endif

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

namespace reeve {
namespace {

// Tells the core that this is a spin loop (eases the sibling hyperthread).
inline void relax() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#else
  std::this_thread::yield();
#endif
}

// A ticket: the run's generation in the high half; in the low half, the
// next index to take, or kEach for a runEach (each thread its own index).
constexpr std::uint64_t kEach = 1u << 31;
constexpr std::uint64_t kClosed = kEach - 1;  // an index past any run's
std::uint32_t generationOf(std::uint64_t ticket) { return static_cast<std::uint32_t>(ticket >> 32); }

}  // namespace

ThreadPool::ThreadPool(int threads) {
  if (threads < 1) throw std::invalid_argument("thread pool: expected at least 1 thread, got " + std::to_string(threads));
  workers_.reserve(threads - 1);
  for (int t = 1; t < threads; ++t) workers_.emplace_back([this, t] { work(t); });
}

ThreadPool::~ThreadPool() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  for (std::thread& w : workers_) w.join();
}

int ThreadPool::cores() {
  // Not the machine's cores where the process may use fewer: two threads
  // on one allowed core spin-wait against each other (64 Atwood machines
  // under `taskset -c 0`, the default threads: 3.5 times one thread's time).
#ifdef __linux__
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  if (sched_getaffinity(0, sizeof allowed, &allowed) == 0) return std::max(1, CPU_COUNT(&allowed));
#endif
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

template <class Busy>
void ThreadPool::spinWhile(const Busy& busy) const {
  const std::chrono::microseconds spin(spin_us_.load(std::memory_order_relaxed));
  if (spin.count() == 0) return;
  const auto until = std::chrono::steady_clock::now() + spin;
  for (int k = 1; busy(); ++k) {
    if (k % 64 == 0 && std::chrono::steady_clock::now() >= until) return;
    relax();
  }
}

void ThreadPool::runOne(int i, int n) {
  try {
    call_.load(std::memory_order_relaxed)(task_.load(std::memory_order_relaxed), i);
  } catch (...) {
    std::lock_guard lock(mutex_);
    if (!error_) error_ = std::current_exception();
    failed_.store(true, std::memory_order_relaxed);  // published by done_ below
  }
  if (done_.fetch_add(1, std::memory_order_seq_cst) + 1 == n && caller_waits_.load(std::memory_order_seq_cst)) {
    std::lock_guard lock(mutex_);
    finished_.notify_all();
  }
}

void ThreadPool::take(std::uint32_t generation) {
  while (true) {
    std::uint64_t ticket = ticket_.load(std::memory_order_acquire);
    if (generationOf(ticket) != generation) return;
    // n_ is this run's while the ticket is: the next run closes the ticket
    // before it writes n_ (runIndices), so a CAS on a ticket read before
    // that fails.
    const int n = n_.load(std::memory_order_acquire);
    const int i = static_cast<int>(ticket & (kEach - 1));
    if (i >= n) return;
    if (ticket_.compare_exchange_weak(ticket, ticket + 1, std::memory_order_acq_rel)) runOne(i, n);
  }
}

void ThreadPool::work(int id) {
  std::uint32_t seen = 0;
  const auto idle = [&] {
    return generationOf(ticket_.load(std::memory_order_seq_cst)) == seen && !stop_.load(std::memory_order_relaxed);
  };
  while (true) {
    spinWhile(idle);
    if (idle()) {
      std::unique_lock lock(mutex_);
      sleepers_.fetch_add(1, std::memory_order_seq_cst);  // before idle() reads the ticket again
      wake_.wait(lock, [&] { return !idle(); });
      sleepers_.fetch_sub(1, std::memory_order_relaxed);
    }
    if (stop_) return;
    const std::uint64_t ticket = ticket_.load(std::memory_order_acquire);
    seen = generationOf(ticket);
    // A runEach waits for every thread's index, so its n_ and task are
    // still those of the run this ticket is.
    if (ticket & kEach) runOne(id, n_.load(std::memory_order_relaxed));
    else take(seen);
  }
}

void ThreadPool::runIndices(int n, Call call, const void* task, bool each) {
  if (n <= 0) return;
  // The last run's ticket closed first: a thread that read it before its
  // last index was taken would otherwise take that index again, of this
  // run's n and task (take()).
  ticket_.store(static_cast<std::uint64_t>(generation_) << 32 | kClosed, std::memory_order_relaxed);
  call_.store(call, std::memory_order_relaxed);
  task_.store(task, std::memory_order_relaxed);
  n_.store(n, std::memory_order_release);
  done_.store(0, std::memory_order_relaxed);
  ++generation_;
  ticket_.store(static_cast<std::uint64_t>(generation_) << 32 | (each ? kEach : 0), std::memory_order_seq_cst);
  // A worker counts itself asleep, under the lock, before it reads the
  // ticket a last time: if it has not seen this one, it is counted here,
  // and holds the lock until it waits.
  if (n > 1 && sleepers_.load(std::memory_order_seq_cst) > 0) {
    std::lock_guard lock(mutex_);
    wake_.notify_all();
  }
  if (each) runOne(0, n);
  else take(generation_);
  // Every index is taken; wait for those still running elsewhere.
  const auto running = [&] { return done_.load(std::memory_order_seq_cst) < n; };
  spinWhile(running);
  if (running()) {
    std::unique_lock lock(mutex_);
    caller_waits_.store(true, std::memory_order_seq_cst);  // before running() reads done_ again
    finished_.wait(lock, [&] { return !running(); });
    caller_waits_.store(false, std::memory_order_relaxed);
  }
  if (!failed_.load(std::memory_order_relaxed)) return;  // done_ read above published it
  std::exception_ptr error;
  {
    std::lock_guard lock(mutex_);
    error = std::exchange(error_, nullptr);
    failed_.store(false, std::memory_order_relaxed);
  }
  std::rethrow_exception(error);
}

}  // namespace reeve
