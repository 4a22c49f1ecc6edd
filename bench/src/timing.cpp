#include "reeve/bench/timing.h"

#include <algorithm>
#include <chrono>
#include <vector>

namespace reeve::bench {

namespace {

void warmUp(FrameRun& run, const TimingOptions& options) {
  if (options.warmup_frames <= 0) return;
  run.reset();
  for (int f = 0; f < options.warmup_frames; ++f) run.step();
}

// The frames of a run on the clock: all but its first, which holds the
// engine's one-time work on a model just built (Reeve's solver layout and
// symbolic factorization; MuJoCo's compile is in its model's constructor,
// off the clock), where a run has more than one.
int timedFrames(int frames) { return frames > 1 ? frames - 1 : std::max(1, frames); }

// One run: reset, then `frames` steps, those after the first on the clock.
// Returns the ms per timed frame; adds the timed frames' iterations.
double timeRun(FrameRun& run, int frames, bool observe, long& iterations) {
  using Clock = std::chrono::steady_clock;
  run.reset();
  double seconds = 0.0;
  for (int f = 0; f < frames; ++f) {
    const auto t0 = Clock::now();
    run.step();
    const auto t1 = Clock::now();
    if (f > 0 || frames == 1) {
      seconds += std::chrono::duration<double>(t1 - t0).count();
      iterations += run.lastIterations();
    }
    if (observe) run.observe(f);
  }
  return 1e3 * seconds / timedFrames(frames);
}

FrameTiming summary(std::vector<double> ms, long iterations, int frames) {
  std::sort(ms.begin(), ms.end());
  FrameTiming t;
  t.runs = static_cast<int>(ms.size());
  t.min_ms = ms.front();
  t.max_ms = ms.back();
  t.median_ms = ms.size() % 2 ? ms[ms.size() / 2] : 0.5 * (ms[ms.size() / 2 - 1] + ms[ms.size() / 2]);
  t.iterations_per_frame = static_cast<double>(iterations) / (static_cast<double>(t.runs) * timedFrames(frames));
  return t;
}

}  // namespace

FrameTiming timeFrames(FrameRun& run, int frames, const TimingOptions& options) {
  warmUp(run, options);
  std::vector<double> ms;
  long iterations = 0;
  double timed = 0.0;
  for (int r = 0; r < std::max(1, options.repeats) && (r == 0 || timed < options.max_seconds); ++r) {
    const double frame_ms = timeRun(run, frames, r == 0 || options.observe_every_run, iterations);
    timed += 1e-3 * frame_ms * timedFrames(frames);
    ms.push_back(frame_ms);
  }
  return summary(std::move(ms), iterations, frames);
}

std::pair<FrameTiming, FrameTiming> timeFramesInTurn(FrameRun& a, FrameRun& b, int frames,
                                                     const TimingOptions& options) {
  warmUp(a, options);
  warmUp(b, options);
  std::vector<double> ms_a, ms_b;
  long iterations_a = 0, iterations_b = 0;
  double timed = 0.0;
  for (int r = 0; r < std::max(1, options.repeats) && (r == 0 || timed < options.max_seconds); ++r) {
    const bool observe = r == 0 || options.observe_every_run;
    double ms_of_a, ms_of_b;
    if (r % 2 == 0) {
      ms_of_a = timeRun(a, frames, observe, iterations_a);
      ms_of_b = timeRun(b, frames, observe, iterations_b);
    } else {
      ms_of_b = timeRun(b, frames, observe, iterations_b);
      ms_of_a = timeRun(a, frames, observe, iterations_a);
    }
    timed += 1e-3 * (ms_of_a + ms_of_b) * timedFrames(frames);
    ms_a.push_back(ms_of_a);
    ms_b.push_back(ms_of_b);
  }
  return {summary(std::move(ms_a), iterations_a, frames), summary(std::move(ms_b), iterations_b, frames)};
}

}  // namespace reeve::bench
