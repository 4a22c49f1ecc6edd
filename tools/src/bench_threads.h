// The thread counts a thread bench runs (reeve bench batch, islands), and
// its one-thread baseline timed on each core.
#pragma once

#include <pthread.h>
#include <sched.h>

#include <algorithm>
#include <cstdio>
#include <functional>
#include <stdexcept>
#include <string>
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

/// One thread's time (ms, as `timed` returns it) on each core this process
/// may run on, the calling thread pinned to each in turn and then given
/// back the cores it had. A VM's cores need not be equally fast (DESIGN,
/// "This VM's two cores are not equally fast": 1 and 0.71 measured), and an
/// unpinned one-thread row lands on either. Where pinning fails, one
/// unpinned time.
inline std::vector<double> timeOnEachCore(const std::function<double()>& timed) {
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  if (pthread_getaffinity_np(pthread_self(), sizeof allowed, &allowed) != 0) return {timed()};
  std::vector<double> ms;
  for (int cpu = 0; cpu < CPU_SETSIZE; ++cpu) {
    if (!CPU_ISSET(cpu, &allowed)) continue;
    cpu_set_t one;
    CPU_ZERO(&one);
    CPU_SET(cpu, &one);
    if (pthread_setaffinity_np(pthread_self(), sizeof one, &one) != 0) continue;
    ms.push_back(timed());
  }
  pthread_setaffinity_np(pthread_self(), sizeof allowed, &allowed);
  if (ms.empty()) ms.push_back(timed());
  return ms;
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
