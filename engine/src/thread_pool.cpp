#include "reeve/engine/thread_pool.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

namespace reeve {

ThreadPool::ThreadPool(int threads) {
  if (threads < 1) throw std::invalid_argument("thread pool: expected at least 1 thread, got " + std::to_string(threads));
  workers_.reserve(threads - 1);
  for (int t = 1; t < threads; ++t) workers_.emplace_back([this] { work(); });
}

ThreadPool::~ThreadPool() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  for (std::thread& w : workers_) w.join();
}

int ThreadPool::cores() { return std::max(1u, std::thread::hardware_concurrency()); }

void ThreadPool::drain(std::unique_lock<std::mutex>& lock) {
  while (next_ < n_) {
    const int i = next_++;
    lock.unlock();
    std::exception_ptr failed;
    try {
      (*task_)(i);
    } catch (...) {
      failed = std::current_exception();
    }
    lock.lock();
    if (failed && !error_) error_ = failed;
  }
}

void ThreadPool::work() {
  std::uint64_t seen = 0;
  std::unique_lock lock(mutex_);
  while (true) {
    wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
    if (stop_) return;
    seen = generation_;
    ++running_;
    drain(lock);
    if (--running_ == 0) done_.notify_all();
  }
}

void ThreadPool::run(int n, const std::function<void(int)>& task) {
  if (n <= 0) return;
  std::unique_lock lock(mutex_);
  task_ = &task;
  n_ = n;
  next_ = 0;
  error_ = nullptr;
  ++generation_;
  if (!workers_.empty() && n > 1) wake_.notify_all();
  drain(lock);
  // Every index is handed out; wait for the workers still inside one. A
  // worker that wakes later finds nothing left and goes back to sleep.
  done_.wait(lock, [&] { return running_ == 0; });
  task_ = nullptr;
  n_ = next_ = 0;
  if (std::exception_ptr e = std::exchange(error_, nullptr)) {
    lock.unlock();
    std::rethrow_exception(e);
  }
}

}  // namespace reeve
