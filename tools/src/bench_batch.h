// `reeve bench batch`: copies of the shipped machines stepped side by side
// (reeve.Batch's stepBatch) on 1 and more threads: ms per scene-frame and
// the speed-up over one thread (issue 30). Prints; never passes or fails.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "reeve/bench/report.h"

namespace reeve {

struct BatchBenchOptions {
  bench::Output output;
  std::filesystem::path scenes_dir;
  std::vector<std::string> scenes = {"atwood", "hand", "hilbert2", "hilbert3"};  ///< file names without .json
  int copies = 64;
  std::vector<int> threads;  ///< default: 1, 2 and the cores (once each)
  int frames = 30;           ///< timed frames per run
  int repeats = 3;           ///< timed runs per row; the median is reported
};

/// Runs the benchmark; returns the exit code. Throws SceneError for a
/// scene that does not load, bench::OutputError for an output, and
/// std::invalid_argument for a scene file that does not exist or copies,
/// threads, frames or repeats below 1.
int benchBatch(const BatchBenchOptions& options);

}  // namespace reeve
