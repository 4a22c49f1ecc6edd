#include "reeve/bench/timing.h"

#include <algorithm>
#include <chrono>
#include <vector>

namespace reeve::bench {

FrameTiming timeFrames(FrameRun& run, int frames, const TimingOptions& options) {
  using Clock = std::chrono::steady_clock;
  if (options.warmup_frames > 0) {
    run.reset();
    for (int f = 0; f < options.warmup_frames; ++f) run.step();
  }
  std::vector<double> ms;
  long iterations = 0;
  double timed = 0.0;
  for (int r = 0; r < std::max(1, options.repeats) && (r == 0 || timed < options.max_seconds); ++r) {
    run.reset();
    double seconds = 0.0;
    for (int f = 0; f < frames; ++f) {
      const auto t0 = Clock::now();
      run.step();
      seconds += std::chrono::duration<double>(Clock::now() - t0).count();
      iterations += run.lastIterations();
      if (r == 0 || options.observe_every_run) run.observe(f);
    }
    timed += seconds;
    ms.push_back(1e3 * seconds / std::max(1, frames));
  }
  std::sort(ms.begin(), ms.end());
  FrameTiming t;
  t.runs = static_cast<int>(ms.size());
  t.min_ms = ms.front();
  t.max_ms = ms.back();
  t.median_ms = ms.size() % 2 ? ms[ms.size() / 2] : 0.5 * (ms[ms.size() / 2 - 1] + ms[ms.size() / 2]);
  t.iterations_per_frame = static_cast<double>(iterations) / (static_cast<double>(t.runs) * std::max(1, frames));
  return t;
}

}  // namespace reeve::bench
