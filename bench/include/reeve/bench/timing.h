// The one timing loop of the benchmarks: a model run from its start
// several times, only its frame steps on the clock.
#pragma once

#include <functional>
#include <utility>

#include "reeve/scene/scene.h"

namespace reeve::bench {

/// Something to time frame by frame. reset() builds it afresh (not
/// timed), step() advances one frame (timed), observe(frame) reads it
/// after step number `frame` (0-based; not timed).
class FrameRun {
 public:
  virtual ~FrameRun() = default;
  virtual void reset() = 0;
  virtual void step() = 0;
  virtual void observe(int /*frame*/) {}
  /// Solver iterations the last step() ran (0 when unknown).
  virtual int lastIterations() const { return 0; }
};

/// A scene from `make`, stepped at its frame rate.
class SceneRun : public FrameRun {
 public:
  explicit SceneRun(std::function<Scene()> make) : make_(std::move(make)) {}
  void reset() override { scene_ = make_(); }
  void step() override { scene_.world->step(1.0 / scene_.frame_rate_hz); }
  int lastIterations() const override { return scene_.world->lastStepIterations(); }
  Scene& scene() { return scene_; }

 private:
  std::function<Scene()> make_;
  Scene scene_;
};

struct TimingOptions {
  int repeats = 5;            ///< timed runs (at least 1)
  int warmup_frames = 30;     ///< stepped untimed on a first, separate run
  double max_seconds = 1e9;   ///< stop repeating once this much was timed
  bool observe_every_run = false;  ///< else observe() runs in the first timed run only
};

/// ms per frame over the timed runs (each of `frames` frames), and the
/// solver iterations run per frame (mean over the timed frames).
struct FrameTiming {
  double min_ms = 0, median_ms = 0, max_ms = 0;
  double iterations_per_frame = 0;
  int runs = 0;
};

/// Warms `run` up (reset, options.warmup_frames steps), then times
/// options.repeats runs of reset + `frames` steps: ms per frame of each
/// run's steps after its first, which holds an engine's one-time work on
/// a model just built (Reeve's solver layout and symbolic factorization:
/// the K = 32 chain's first frame costs about 6 of its later ones, 8 % of
/// a 60-frame run). Exceptions from the run propagate.
FrameTiming timeFrames(FrameRun& run, int frames, const TimingOptions& options);

/// timeFrames of two runs whose times are compared, their timed runs
/// taken in turn (a, b, then b, a, ...), so that both see the machine as
/// it was over the same stretch of time: a ratio of two medians timed one
/// after the other moved by 5 to 10 % between invocations, as the machine
/// sped up and slowed down (reeve bench peers).
std::pair<FrameTiming, FrameTiming> timeFramesInTurn(FrameRun& a, FrameRun& b, int frames,
                                                     const TimingOptions& options);

}  // namespace reeve::bench
