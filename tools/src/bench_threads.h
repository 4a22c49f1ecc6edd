// The thread counts a thread bench runs (reeve bench batch, islands), its
// one-thread baseline timed on each core, and one thread timed on each of
// several cores at once: the ceiling that busy cores leave.
#pragma once

#include <pthread.h>
#include <sched.h>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <functional>
#include <latch>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "reeve/engine/thread_pool.h"

namespace reeve {

/// `asked` (empty: 1, 2 and the cores), increasing, each once, with 1
/// first as the speed-up's baseline. Throws std::invalid_argument for a
/// count below 1.
inline std::vector<int> threadCounts(std::vector<int> asked) {
  if (asked.empty()) asked = {1, 2, ThreadPool::cores()};
  std::sort(asked.begin(), asked.end());
  asked.erase(std::unique(asked.begin(), asked.end()), asked.end());
  if (asked.front() < 1) throw std::invalid_argument("--threads: expected counts of at least 1");
  if (asked.front() != 1) asked.insert(asked.begin(), 1);
  return asked;
}

/// The median of `runs` (ms; the upper one of an even count), not empty.
inline double median(std::vector<double> runs) {
  std::sort(runs.begin(), runs.end());
  return runs[runs.size() / 2];
}

/// The cores this process may run on (CPU numbers, increasing); empty
/// where they cannot be read.
inline std::vector<int> allowedCores() {
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  if (pthread_getaffinity_np(pthread_self(), sizeof allowed, &allowed) != 0) return {};
  std::vector<int> cores;
  for (int cpu = 0; cpu < CPU_SETSIZE; ++cpu)
    if (CPU_ISSET(cpu, &allowed)) cores.push_back(cpu);
  return cores;
}

/// Pins the calling thread to `cpu`; false where that fails.
inline bool pinTo(int cpu) {
  cpu_set_t one;
  CPU_ZERO(&one);
  CPU_SET(cpu, &one);
  return pthread_setaffinity_np(pthread_self(), sizeof one, &one) == 0;
}

/// One thread's time (ms, as `timed` returns it) on each of `cores`
/// (allowedCores()), the calling thread pinned to each in turn and then
/// given back the cores it had. A VM's cores need not be equally fast
/// (DESIGN, "This VM's two cores are not equally fast": 1 and 0.71
/// measured), and an unpinned one-thread row lands on either. Where
/// pinning fails, one unpinned time.
inline std::vector<double> timeOnEachCore(const std::function<double()>& timed, const std::vector<int>& cores) {
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  if (cores.empty() || pthread_getaffinity_np(pthread_self(), sizeof allowed, &allowed) != 0) return {timed()};
  std::vector<double> ms;
  for (const int cpu : cores)
    if (pinTo(cpu)) ms.push_back(timed());
  pthread_setaffinity_np(pthread_self(), sizeof allowed, &allowed);
  if (ms.size() != cores.size()) return {timed()};
  return ms;
}

/// `timed` on one thread per entry of `cores`, each pinned to its core
/// (unpinned for -1, or where pinning fails) and all started together:
/// each thread's time (ms). A VM's cores can slow each other while all
/// are busy (the host's other work), which timeOnEachCore, one core at a
/// time, does not show. `timed` must be safe to run on several threads at
/// once (each run stepping a World of its own).
inline std::vector<double> timeOnCoresAtOnce(const std::function<double()>& timed, const std::vector<int>& cores) {
  std::vector<double> ms(cores.size());
  std::latch start(static_cast<std::ptrdiff_t>(cores.size()));
  std::exception_ptr error;
  std::mutex error_mutex;
  {
    std::vector<std::jthread> threads;
    for (std::size_t i = 0; i < cores.size(); ++i)
      threads.emplace_back([&, i] {
        if (cores[i] >= 0) pinTo(cores[i]);
        start.arrive_and_wait();
        try {
          ms[i] = timed();
        } catch (...) {
          const std::lock_guard lock(error_mutex);
          if (!error) error = std::current_exception();
        }
      });
  }  // joined
  if (error) std::rethrow_exception(error);
  return ms;
}

/// The `threads` fastest of `cores` by one thread's time on each
/// (`per_core`, ms, in the order of `cores`), fastest first; where the
/// cores were not timed one by one (timeOnEachCore's one unpinned time),
/// `threads` unpinned slots (-1).
inline std::vector<int> fastestCores(const std::vector<int>& cores, const std::vector<double>& per_core,
                                     int threads) {
  if (per_core.size() != cores.size()) return std::vector<int>(std::max(threads, 0), -1);
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < per_core.size() && i < cores.size(); ++i) order.push_back(i);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return per_core[a] < per_core[b]; });
  std::vector<int> fastest;
  for (std::size_t i = 0; i < order.size() && static_cast<int>(fastest.size()) < threads; ++i)
    fastest.push_back(cores[order[i]]);
  return fastest;
}

/// The most that threads side by side can run over one thread alone on
/// the fastest core (`one`, ms), given each one's time with all their
/// cores busy at once (`busy`, ms, timeOnCoresAtOnce): the rates summed,
/// the sum of one / busy[i].
inline double busySpeedup(double one, const std::vector<double>& busy) {
  double rate = 0.0;
  for (const double ms : busy) rate += one / ms;
  return rate;
}

/// The most that `threads` threads can run over the fastest core alone,
/// given one thread's time on each core (`per_core`, ms): the rates of
/// the `threads` fastest cores summed, over the fastest's.
inline double idealSpeedup(std::vector<double> per_core, int threads) {
  std::sort(per_core.begin(), per_core.end());
  double rate = 0.0;
  for (int i = 0; i < threads && i < static_cast<int>(per_core.size()); ++i) rate += per_core.front() / per_core[i];
  return rate;
}

/// "# <what>, one thread on each core: 1.01, 1.41 <unit>", a header line
/// of the table.
inline void printCoreTimes(const std::string& what, const std::vector<double>& per_core, const char* unit) {
  std::printf("# %s, one thread on each core:", what.c_str());
  for (std::size_t i = 0; i < per_core.size(); ++i) std::printf("%s %.4g", i == 0 ? "" : ",", per_core[i]);
  std::printf(" %s\n", unit);
}

}  // namespace reeve
