// The thread pool under ThreadSanitizer (tools/sanitize.sh): many short
// runs on 1 to 8 threads, spinning and sleeping between them, runs that
// pin each thread to its index (runEach) mixed in, a task that throws,
// and every index run once.
#include <atomic>
#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <vector>

#include "reeve/engine/thread_pool.h"

int main() {
  for (const int threads : {1, 2, 4, 8}) {
    reeve::ThreadPool pool(threads);
    std::vector<long> data(1000, 0), each(threads, 0);
    for (int call = 0; call < 500; ++call) {
      if (call == 250) pool.setSpin(std::chrono::microseconds(100));  // then they spin between runs
      pool.run(1000, [&](int i) { data[i] += i; });
      pool.run(3, [&](int i) { data[i] += 1; });
      pool.runEach([&](int t) { each[t] += t + 1; });
    }
    for (int t = 0; t < threads; ++t)
      if (each[t] != 500L * (t + 1)) {
        std::fprintf(stderr, "%d threads: runEach gave thread %d %ld\n", threads, t, each[t]);
        return 1;
      }
    std::atomic<int> ran{0};
    try {
      pool.run(10, [&](int i) {
        ++ran;
        if (i == 3) throw std::runtime_error("index 3");
      });
      return 1;  // not rethrown
    } catch (const std::runtime_error&) {
    }
    long sum = 0;
    for (const long d : data) sum += d;
    if (sum != 500L * (999L * 1000 / 2 + 3) || ran != 10) {
      std::fprintf(stderr, "%d threads: sum %ld, ran %d\n", threads, sum, ran.load());
      return 1;
    }
  }
  std::puts("thread pool: every index once on 1, 2, 4 and 8 threads");
}
